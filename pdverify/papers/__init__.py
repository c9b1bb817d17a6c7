"""The published PD beam formulations, one package per paper, each with the same file roles:

- ``model.py``: the model(s) as :class:`~pdverify.core.contract.Model` objects (options, variants, capabilities,
  solve);
- kernels and operators (``operator.py``, ``kernels.py``, ``bonds.py``, ``assembly.py``): the paper's discrete
  equations as pure functions, arrays in, arrays out;
- ``ends.py``: the boundary treatment (fictitious points, mirror images, end rows) and loads;
- ``transient.py`` (and its step engines): time integration, where the paper has dynamics.

Each package's ``__init__`` gives the citation, a map from the paper's equations to the functions that
implement them, and ``MODELS`` (what the registry collects). docs/models/<paper>.md is the guide.

======================  ==========================================================  =================================
package                 paper                                                       models
======================  ==========================================================  =================================
``diyaroglu``           Diyaroglu, Oterkus & Oterkus 2017 (MMS)                     pd-eb
``moyer``               Moyer & Miraglia 2014 (JAMP)                                pd-rod, pd-timoshenko, pd-torsion
``yang``                Yang, Oterkus & Oterkus 2020 (JPER)                         pd-higher-order
``ogrady``              O'Grady & Foster 2014 (IJSS)                                pd-bond-pair
``curved``              PD curved Timoshenko–Ehrenfest beam with PDDO functions     pd-curved, pd-curved-mms
======================  ==========================================================  =================================
"""
