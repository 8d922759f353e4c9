"""vctools: pre- and post-processing for vemcontact (meshing, plots, regression comparison)."""

__version__ = "0.1.0"
