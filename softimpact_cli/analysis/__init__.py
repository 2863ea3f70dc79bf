"""Analyses: orchestrate kernels and return labelled ``xarray.Dataset`` objects.

They never write files, never import matplotlib, never read TOML.
"""
