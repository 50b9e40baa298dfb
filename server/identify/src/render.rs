//! Synthetic marker images: renders dot markers at given positions into grayscale PNGs with blur and noise.
//!
//! Each dot is a uniform disc, anti-aliased by supersampling the pixels its edge crosses, then the
//! whole image is blurred with a separable Gaussian and seeded Gaussian noise is added before
//! rounding to 8 bits. The disc and the blur are radially symmetric about the dot's centre, so the
//! intensity centroid of a rendered dot is its centre (up to the supersampling, ~10⁻³ px): what
//! the tracker measures is comparable with the truth the images were made from.
//!
//! [`render_sequence`] turns marker tracks ([`MarkerTracks`], pixel columns) into
//! `frame_0000.png, frame_0001.png, …` plus `frames.csv` (`frame,t_s,file`), the input of
//! `needlesim-lab identify track`. Markers whose `detected` flag is 0 in the tracks are not
//! drawn, which is how a test makes a missing detection.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use rand::{Rng, SeedableRng, rngs::SmallRng};

use crate::frame::GrayImage;
use crate::track::Polarity;
use crate::tracks::MarkerTracks;

/// How synthetic marker images look.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderParams {
    /// Image width, pixels.
    pub width_px: u32,
    /// Image height, pixels.
    pub height_px: u32,
    /// Radius of each dot, pixels.
    pub dot_radius_px: f64,
    /// Dark dots on a bright background, or bright dots on a dark one.
    pub polarity: Polarity,
    /// Background gray level (0–255).
    pub background: f64,
    /// Difference between a dot's inside and the background, gray levels (darker for
    /// [`Polarity::Dark`], brighter for [`Polarity::Bright`]).
    pub contrast: f64,
    /// Standard deviation of the Gaussian blur, pixels (0: no blur).
    pub blur_sigma_px: f64,
    /// Standard deviation of the additive Gaussian noise, gray levels (0: none).
    pub noise_sigma: f64,
    /// Seed of the noise; each frame mixes it with its own frame seed.
    pub seed: u64,
}

impl Default for RenderParams {
    /// 640 × 480, dark dots of radius 4 px (background 200, contrast 120), blur σ 1 px, noise σ 3.
    fn default() -> Self {
        Self {
            width_px: 640,
            height_px: 480,
            dot_radius_px: 4.0,
            polarity: Polarity::Dark,
            background: 200.0,
            contrast: 120.0,
            blur_sigma_px: 1.0,
            noise_sigma: 3.0,
            seed: 0,
        }
    }
}

impl RenderParams {
    /// Checks the parameters; the error names the offending one.
    pub fn validate(&self) -> Result<()> {
        if self.width_px == 0 || self.height_px == 0 || self.width_px > 8192 || self.height_px > 8192 {
            bail!("render: image size {}×{} must be between 1 and 8192 pixels per side", self.width_px, self.height_px);
        }
        let finite_nonneg = |v: f64, name: &str| -> Result<()> {
            if !v.is_finite() || v < 0.0 {
                bail!("render: {name} must be a finite number ≥ 0, got {v}");
            }
            Ok(())
        };
        finite_nonneg(self.dot_radius_px, "dot radius")?;
        finite_nonneg(self.background, "background")?;
        finite_nonneg(self.contrast, "contrast")?;
        finite_nonneg(self.blur_sigma_px, "blur sigma")?;
        finite_nonneg(self.noise_sigma, "noise sigma")?;
        if self.dot_radius_px <= 0.0 {
            bail!("render: dot radius must be > 0");
        }
        if self.blur_sigma_px > 100.0 {
            bail!("render: blur sigma {} px is larger than 100 px", self.blur_sigma_px);
        }
        Ok(())
    }
}

/// Supersampling factor per axis for pixels crossed by a dot's edge.
const SUPERSAMPLE: usize = 16;

/// Renders one frame with dots at `centres_px` (x right, y down, pixel centres at integer
/// coordinates: the pixel `(i, j)` covers `[i − ½, i + ½] × [j − ½, j + ½]`). Dots may lie partly
/// or wholly outside the image (clipped). `frame_seed` is mixed with `p.seed` for the noise, so
/// each frame of a sequence has its own noise and the same call always gives the same image.
///
/// Panics never; parameters out of range are clamped where harmless (call
/// [`RenderParams::validate`] first to reject them).
pub fn render_frame(centres_px: &[[f64; 2]], p: &RenderParams, frame_seed: u64) -> GrayImage {
    let (w, h) = (p.width_px.max(1) as usize, p.height_px.max(1) as usize);
    let mut cover = vec![0.0f32; w * h];
    let r = p.dot_radius_px.max(0.0);
    for c in centres_px.iter().filter(|c| c[0].is_finite() && c[1].is_finite()) {
        add_disc(&mut cover, w, h, *c, r);
    }
    if p.blur_sigma_px > 0.0 {
        cover = gaussian_blur(&cover, w, h, p.blur_sigma_px.min(100.0));
    }
    let sign = match p.polarity {
        Polarity::Dark => -1.0,
        Polarity::Bright => 1.0,
    };
    let mut rng = SmallRng::seed_from_u64(splitmix64(p.seed ^ splitmix64(frame_seed.wrapping_add(0x9E37_79B9_7F4A_7C15))));
    let mut normals = NormalPairs::default();
    let mut img = GrayImage::new(w as u32, h as u32);
    for (px, c) in img.as_mut_raw().iter_mut().zip(&cover) {
        let mut v = p.background + sign * p.contrast * f64::from(*c);
        if p.noise_sigma > 0.0 {
            v += p.noise_sigma * normals.next(&mut rng);
        }
        *px = v.round().clamp(0.0, 255.0) as u8;
    }
    img
}

/// Adds the coverage of the disc of radius `r` at `c` to `cover` (coverage of overlapping dots
/// adds up; callers keep dots apart).
fn add_disc(cover: &mut [f32], w: usize, h: usize, c: [f64; 2], r: f64) {
    let x0 = (c[0] - r - 1.0).floor().max(0.0);
    let x1 = (c[0] + r + 1.0).ceil().min(w as f64 - 1.0);
    let y0 = (c[1] - r - 1.0).floor().max(0.0);
    let y1 = (c[1] + r + 1.0).ceil().min(h as f64 - 1.0);
    if x0 > x1 || y0 > y1 {
        return;
    }
    let r2 = r * r;
    let half_diag = std::f64::consts::FRAC_1_SQRT_2;
    for j in y0 as usize..=y1 as usize {
        for i in x0 as usize..=x1 as usize {
            let (dx, dy) = (i as f64 - c[0], j as f64 - c[1]);
            let d = (dx * dx + dy * dy).sqrt();
            let f = if d + half_diag <= r {
                1.0
            } else if d - half_diag >= r {
                0.0
            } else {
                // The edge crosses this pixel: count subsample points inside the disc.
                let n = SUPERSAMPLE;
                let mut inside = 0usize;
                for sj in 0..n {
                    let sy = dy - 0.5 + (sj as f64 + 0.5) / n as f64;
                    for si in 0..n {
                        let sx = dx - 0.5 + (si as f64 + 0.5) / n as f64;
                        inside += usize::from(sx * sx + sy * sy <= r2);
                    }
                }
                inside as f64 / (n * n) as f64
            };
            cover[j * w + i] += f as f32;
        }
    }
}

/// Separable Gaussian blur with a kernel truncated at 4σ and mirrored borders.
fn gaussian_blur(src: &[f32], w: usize, h: usize, sigma: f64) -> Vec<f32> {
    let rad = (4.0 * sigma).ceil() as isize;
    let mut k: Vec<f32> = (-rad..=rad).map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp() as f32).collect();
    let sum: f32 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= sum);
    let mirror = |i: isize, n: usize| -> usize {
        let n = n as isize;
        let mut i = i;
        // Reflect until inside (a kernel wider than the image reflects more than once).
        loop {
            if i < 0 {
                i = -i - 1;
            } else if i >= n {
                i = 2 * n - i - 1;
            } else {
                return i as usize;
            }
        }
    };
    let mut tmp = vec![0.0f32; w * h];
    for y in 0..h {
        let row = &src[y * w..(y + 1) * w];
        for x in 0..w {
            let mut acc = 0.0f32;
            for (t, kv) in k.iter().enumerate() {
                acc += kv * row[mirror(x as isize + t as isize - rad, w)];
            }
            tmp[y * w + x] = acc;
        }
    }
    let mut out = vec![0.0f32; w * h];
    for y in 0..h {
        for (t, kv) in k.iter().enumerate() {
            let sy = mirror(y as isize + t as isize - rad, h);
            let (dst, srow) = (&mut out[y * w..(y + 1) * w], &tmp[sy * w..(sy + 1) * w]);
            for (d, s) in dst.iter_mut().zip(srow) {
                *d += kv * s;
            }
        }
    }
    out
}

/// Standard normal samples by the Box–Muller transform, two per pair of uniforms.
#[derive(Default)]
struct NormalPairs {
    spare: Option<f64>,
}

impl NormalPairs {
    fn next(&mut self, rng: &mut impl Rng) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]: ln is finite
        let u2: f64 = rng.random::<f64>();
        let r = (-2.0 * u1.ln()).sqrt();
        let a = std::f64::consts::TAU * u2;
        self.spare = Some(r * a.sin());
        r * a.cos()
    }
}

/// A 64-bit mixing function (SplitMix64's finaliser), to derive per-frame seeds.
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Renders every frame of `tracks` (pixel positions; markers with `detected = false` are left
/// out) into `dir` as `frame_0000.png, …` and writes `dir/frames.csv` (`frame,t_s,file`).
/// Creates `dir` if needed and returns the image paths in frame order.
///
/// Errors: invalid parameters ([`RenderParams::validate`]), tracks with no frames, a directory
/// or file that cannot be created or written (the error names the path).
pub fn render_sequence(tracks: &MarkerTracks, p: &RenderParams, dir: &Path) -> Result<Vec<PathBuf>> {
    p.validate()?;
    let n = tracks.n_markers;
    if tracks.n_frames() == 0 || tracks.positions_px.len() != tracks.n_frames() * n || tracks.detected.len() != tracks.n_frames() * n {
        bail!("render: the marker tracks have no frames or inconsistent lengths");
    }
    std::fs::create_dir_all(dir).with_context(|| format!("render: cannot create {}", dir.display()))?;
    let mut paths = Vec::with_capacity(tracks.n_frames());
    let mut index = String::from("frame,t_s,file\n");
    for f in 0..tracks.n_frames() {
        let centres: Vec<[f64; 2]> = (0..n).filter(|&m| tracks.detected[f * n + m]).map(|m| tracks.positions_px[f * n + m]).collect();
        let img = render_frame(&centres, p, f as u64);
        let name = format!("frame_{f:04}.png");
        let path = dir.join(&name);
        let png = img.to_png().with_context(|| format!("render: cannot encode {}", path.display()))?;
        std::fs::write(&path, png).with_context(|| format!("render: cannot write {}", path.display()))?;
        index.push_str(&format!("{f},{},{name}\n", tracks.times_s[f]));
        paths.push(path);
    }
    let csv = dir.join("frames.csv");
    std::fs::write(&csv, index).with_context(|| format!("render: cannot write {}", csv.display()))?;
    Ok(paths)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Intensity centroid of `img` (background-subtracted, dark dots) over the whole image.
    fn centroid(img: &GrayImage, bg: f64) -> [f64; 2] {
        let (mut sw, mut sx, mut sy) = (0.0, 0.0, 0.0);
        let width = img.width() as usize;
        for (i, &v) in img.as_raw().iter().enumerate() {
            let w = bg - f64::from(v);
            sw += w;
            sx += w * (i % width) as f64;
            sy += w * (i / width) as f64;
        }
        [sx / sw, sy / sw]
    }

    #[test]
    fn a_noiseless_dot_has_its_centre_as_centroid_and_the_right_mass() {
        for (k, c) in [[20.0, 20.0], [20.3, 19.71], [19.5, 20.5], [21.123, 18.876]].into_iter().enumerate() {
            let p =
                RenderParams { width_px: 41, height_px: 41, noise_sigma: 0.0, background: 250.0, contrast: 200.0, ..Default::default() };
            // No noise, and a high contrast so that 8-bit rounding is negligible.
            let img = render_frame(&[c], &p, k as u64);
            let g = centroid(&img, 250.0);
            assert!((g[0] - c[0]).abs() < 0.01 && (g[1] - c[1]).abs() < 0.01, "{g:?} vs {c:?}");
            let mass: f64 = img.as_raw().iter().map(|&v| 250.0 - f64::from(v)).sum();
            let expect = 200.0 * std::f64::consts::PI * 16.0;
            assert!((mass / expect - 1.0).abs() < 0.01, "mass {mass} vs {expect}");
        }
    }

    #[test]
    fn noise_is_seeded_and_has_the_requested_sigma() {
        let p = RenderParams { width_px: 200, height_px: 100, noise_sigma: 5.0, background: 128.0, ..Default::default() };
        let a = render_frame(&[], &p, 3);
        assert_eq!(a, render_frame(&[], &p, 3));
        assert_ne!(a, render_frame(&[], &p, 4));
        let v: Vec<f64> = a.as_raw().iter().map(|&v| f64::from(v) - 128.0).collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        assert!(mean.abs() < 0.1 && (sd - 5.0).abs() < 0.15, "mean {mean} sd {sd}");
    }

    #[test]
    fn bad_parameters_are_rejected_by_name() {
        let p = RenderParams { blur_sigma_px: f64::NAN, ..Default::default() };
        assert!(p.validate().unwrap_err().to_string().contains("blur sigma"));
        let p = RenderParams { width_px: 0, ..Default::default() };
        assert!(p.validate().unwrap_err().to_string().contains("image size"));
    }
}
