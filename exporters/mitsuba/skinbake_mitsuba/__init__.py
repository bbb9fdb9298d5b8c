"""Mitsuba 3 side of skinbake: the volumetric ground truth of a layer stack (flat
slab measurements, nested shells under a mesh) and the baked table as a spectral
BSDF. Import skinbake_mitsuba.variant and call choose() before anything that
imports mitsuba."""
