//! Synthetic marker images: renders dot markers at given positions into grayscale PNGs with blur and noise.
