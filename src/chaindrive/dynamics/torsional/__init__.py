"""The torsional builder: shafts, couplings, gear stages, inertias and the chain contour as
elements of one linear model (:class:`~chaindrive.dynamics.torsional.model.model.TorsionalModel`,
docs/torsional.md), its assembly into M, K, C and its modes.
"""
