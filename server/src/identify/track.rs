//! Marker detection (sub-pixel centroids) and frame-to-frame tracking in grayscale phantom images.
