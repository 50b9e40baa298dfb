//! Identification of Young's modulus and Poisson's ratio from a probing experiment by least squares against the FEM model.
