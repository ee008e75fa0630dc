"""Time integration of the whole-drive model: the nonlinear start-up with slack spans, the
rigid run-up, the zero-order-hold step and the compiled kernel (docs/dynamics.md §5).
"""
