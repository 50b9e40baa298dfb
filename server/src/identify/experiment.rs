//! The synthetic experiment generator: probing and needle-insertion experiments simulated with the FEM model, written as marker tracks and force logs.
