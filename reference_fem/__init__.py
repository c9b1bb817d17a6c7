"""scikit-fem reference models standing in for ANSYS BEAM3 and PLANE182."""
