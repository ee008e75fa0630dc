"""Geometry of sprockets (tooth forms) and of the chain contour."""
