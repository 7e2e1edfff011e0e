//! Reference geometry, the hybrid element, assembly, loads, mass and damping.
