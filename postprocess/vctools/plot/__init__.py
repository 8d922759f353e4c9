"""Plots of vemcontact results (contours on polygon meshes)."""
