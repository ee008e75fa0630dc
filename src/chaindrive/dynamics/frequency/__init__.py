"""The frequency response of the whole-drive model: the steady state at the nominal speed, the
speed sweep (AFC), the uncertainty bands and the coefficient of dynamics K_D
(docs/dynamics.md §5).
"""
