"""The linear model of a drive — M, C, K, the motor and machine inputs and the tension-only
spans — the one input of the modal stage, the frequency response and the transient
(:func:`~chaindrive.dynamics.model.build.drive_model`; docs/dynamics.md §1).
"""
