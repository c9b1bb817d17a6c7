"""Local continuum theories that a PD model and its exact reference both use, so that neither imports the
other: the higher-order beam of Yang et al. (:mod:`.higher_order`), the manufactured curved-beam solution
(:mod:`.curved_manufactured`) and where curved-beam theory holds (:mod:`.curved_beam`: the thick ring's warning)."""
