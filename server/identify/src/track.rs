//! Marker detection (sub-pixel centroids) and frame-to-frame tracking in grayscale phantom images.
//!
//! Detection, per frame: the image is turned into a "signal" in which markers are bright (dark
//! markers are inverted) and flattened: a smooth background (tile medians, interpolated
//! bilinearly) is subtracted, so uneven lighting does not matter. A threshold (given, on the raw
//! image; or automatic, on the flattened one: Otsu's, but at least five robust noise standard
//! deviations) splits it into 8-connected blobs; blobs whose area is outside
//! `[min_area_px, max_area_px]` or that touch the image border (their centroids would be biased)
//! are dropped. Each remaining blob's centre is refined to sub-pixel precision by an
//! intensity-weighted centroid of the flattened signal, less the median of a ring around it, over
//! a soft-edged circular window re-centred on the estimate three times (the window's radius is the
//! blob's equivalent radius plus 2 px, kept clear of the nearest neighbour). The centroid of a
//! radially symmetric dot is its centre whatever the window's truncation, so the error is the
//! noise's: about 0.03 px RMS for dots of radius 4 px, contrast 120 and noise σ 4 gray levels
//! (see the tests). Dots must be smaller than the background tiles (an eighth of the image's
//! smaller side, at least 32 px): under half of each tile may be marker.
//!
//! Tracking: markers are numbered in frame 0, row-major from the top-left (rows are split where
//! the sorted y coordinates jump by more than half the median marker spacing). In each later frame
//! every marker's position is predicted at constant velocity from its last two positions, and
//! predictions and detections are paired when they are each other's nearest within
//! `max_jump_px` (repeated on what is left until nothing pairs). A marker left unpaired gets its
//! predicted position with `detected = false`; detections left unpaired (dust, reflections) are
//! ignored. A marker unpaired for more than `max_missing_frames` consecutive frames is an error:
//! the set of markers changed.
//!
//! Pixels to metres ([`Scale`]): image y points down, tissue y up, so
//! `x_m = origin_m.x + (x_px − origin_px.x)·s` and `y_m = origin_m.y − (y_px − origin_px.y)·s`.

use anyhow::{Context, Result, bail};
use needlesim_scene::limit::SizeLimit;

use crate::frame::{GrayImage, decode_png_levels, png_dimensions};
use crate::tracks::MarkerTracks;

/// Whether the markers are darker or brighter than the background.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Polarity {
    /// Dark dots on a bright background.
    Dark,
    /// Bright dots on a dark background.
    Bright,
}

/// How pixels become metres (tissue frame, y up).
#[derive(Debug, Clone, PartialEq)]
pub enum Scale {
    /// A known scale: the pixel `origin_px` is the tissue point `origin_m`.
    MetresPerPixel { m_per_px: f64, origin_px: [f64; 2], origin_m: [f64; 2] },
    /// A known marker spacing: the scale is `spacing_m` over the marker spacing in frame 0 (the
    /// median distance between neighbouring markers, pairs within ±25 % of the median
    /// nearest-neighbour distance), and the frame-0 marker nearest the image's bottom-left corner is
    /// the tissue point `origin_m`.
    MarkerSpacing { spacing_m: f64, origin_m: [f64; 2] },
}

/// Detection and tracking parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackParams {
    /// Dark or bright markers.
    pub polarity: Polarity,
    /// Threshold in gray levels of an 8-bit image (0–255; 16-bit images are scaled to that
    /// range): pixels darker ([`Polarity::Dark`]) or brighter than it are marker pixels. `None`:
    /// automatic, per frame.
    pub threshold: Option<f64>,
    /// Smallest blob kept, pixels (smaller ones are noise).
    pub min_area_px: usize,
    /// Largest blob kept, pixels (larger ones are not markers: the needle, an edge, a shadow).
    pub max_area_px: usize,
    /// Largest distance between a marker's predicted position and its detection, pixels; keep it
    /// below half the marker spacing.
    pub max_jump_px: f64,
    /// The number of markers frame 0 must have (`None`: whatever is found).
    pub expected_markers: Option<usize>,
    /// How many consecutive frames a marker may go undetected (filled in by prediction) before
    /// tracking fails.
    pub max_missing_frames: usize,
    /// Pixels to metres.
    pub scale: Scale,
    /// Largest image decoded, pixels (width × height, read from the PNG header before any pixel
    /// is decoded); a larger one is a [`SizeLimit`] error.
    pub max_image_pixels: u64,
}

/// The default of [`TrackParams::max_image_pixels`]: 25 megapixels (a 6000 × 4000 camera image;
/// decoding and tracking hold about 9 bytes per pixel).
pub const DEFAULT_MAX_IMAGE_PIXELS: u64 = 25_000_000;

impl TrackParams {
    /// Defaults for dots a few pixels across: automatic threshold, areas 4–5000 px, jumps up to
    /// 10 px, any number of markers, up to 2 consecutive missing frames.
    pub fn new(polarity: Polarity, scale: Scale) -> Self {
        Self {
            polarity,
            threshold: None,
            min_area_px: 4,
            max_area_px: 5000,
            max_jump_px: 10.0,
            expected_markers: None,
            max_missing_frames: 2,
            scale,
            max_image_pixels: DEFAULT_MAX_IMAGE_PIXELS,
        }
    }

    /// Checks the parameters; the error names the offending one.
    pub fn validate(&self) -> Result<()> {
        if let Some(t) = self.threshold
            && !(t.is_finite() && (0.0..=255.0).contains(&t))
        {
            bail!("track: threshold must be a gray level between 0 and 255, got {t}");
        }
        if self.min_area_px == 0 || self.min_area_px > self.max_area_px {
            bail!("track: need 1 ≤ min area ({}) ≤ max area ({})", self.min_area_px, self.max_area_px);
        }
        if !(self.max_jump_px.is_finite() && self.max_jump_px > 0.0) {
            bail!("track: max jump must be a positive number of pixels, got {}", self.max_jump_px);
        }
        if self.expected_markers == Some(0) {
            bail!("track: expected markers must be at least 1");
        }
        let finite2 = |v: [f64; 2]| v[0].is_finite() && v[1].is_finite();
        match &self.scale {
            Scale::MetresPerPixel { m_per_px, origin_px, origin_m } => {
                if !(m_per_px.is_finite() && *m_per_px > 0.0) {
                    bail!("track: metres per pixel must be positive, got {m_per_px}");
                }
                if !finite2(*origin_px) || !finite2(*origin_m) {
                    bail!("track: the scale's origin must be finite");
                }
            }
            Scale::MarkerSpacing { spacing_m, origin_m } => {
                if !(spacing_m.is_finite() && *spacing_m > 0.0) {
                    bail!("track: marker spacing must be a positive number of metres, got {spacing_m}");
                }
                if !finite2(*origin_m) {
                    bail!("track: the scale's origin must be finite");
                }
            }
        }
        Ok(())
    }
}

/// An image as floating-point "signal" (markers bright), gray levels 0–255.
struct Plane {
    w: usize,
    h: usize,
    v: Vec<f32>,
}

impl Plane {
    fn from_gray8(img: &GrayImage, polarity: Polarity) -> Self {
        let v = img.as_raw().iter().map(|&x| signal(f32::from(x), polarity)).collect();
        Self { w: img.width() as usize, h: img.height() as usize, v }
    }

    /// Gray levels of a decoded PNG (0–255; 16-bit and colour images keep 16-bit precision, as
    /// luma), turned into signal in place.
    fn from_levels(w: usize, h: usize, mut v: Vec<f32>, polarity: Polarity) -> Self {
        v.iter_mut().for_each(|x| *x = signal(*x, polarity));
        Self { w, h, v }
    }
}

fn signal(v: f32, polarity: Polarity) -> f32 {
    match polarity {
        Polarity::Dark => 255.0 - v,
        Polarity::Bright => v,
    }
}

/// What detection found in one image, with the numbers behind the threshold (for messages).
struct Detection {
    centres: Vec<[f64; 2]>,
    background: f64,
    noise: f64,
    threshold: f64,
}

/// Median and robust standard deviation (1.4826 × median absolute deviation) of `v`, from every
/// few-th value (at most ~65 000 of them).
fn median_and_sigma(v: &[f32]) -> (f64, f64) {
    if v.is_empty() {
        return (0.0, 0.0);
    }
    let mut sample: Vec<f32> = v.iter().step_by(v.len().div_ceil(65_536)).copied().collect();
    let k = sample.len() / 2;
    let med = *sample.select_nth_unstable_by(k, f32::total_cmp).1;
    sample.iter_mut().for_each(|x| *x = (*x - med).abs());
    let mad = *sample.select_nth_unstable_by(k, f32::total_cmp).1;
    (f64::from(med), 1.4826 * f64::from(mad))
}

/// The signal minus a smooth background: the medians of tiles (an eighth of the image's smaller
/// side, at least 32 px) interpolated bilinearly between the tiles' centres. Markers must cover
/// less than half of each tile; a linear illumination gradient is removed exactly.
fn flatten(pl: &Plane) -> Plane {
    let (w, h) = (pl.w, pl.h);
    let t = (w.min(h) / 8).max(32);
    let (nx, ny) = (w.div_ceil(t), h.div_ceil(t));
    let mut med = vec![0.0f32; nx * ny];
    let mut buf = Vec::with_capacity(t * t);
    for ty in 0..ny {
        for tx in 0..nx {
            buf.clear();
            let (x0, x1) = (tx * t, ((tx + 1) * t).min(w));
            // Every other pixel of every other row: hundreds of samples, a quarter of the work.
            for y in (ty * t..((ty + 1) * t).min(h)).step_by(2) {
                buf.extend(pl.v[y * w + x0..y * w + x1].iter().step_by(2));
            }
            let k = buf.len() / 2;
            med[ty * nx + tx] = *buf.select_nth_unstable_by(k, f32::total_cmp).1;
        }
    }
    // Per column (row): the two tiles to interpolate between and the weight of the second.
    let axis = |n: usize, tiles: usize| -> Vec<(usize, usize, f32)> {
        let centre = |i: usize| (i * t + ((i + 1) * t).min(n) - 1) as f32 / 2.0;
        (0..n)
            .map(|x| {
                let i = (x / t).min(tiles - 1);
                let (lo, hi) = if (x as f32) < centre(i) { (i.saturating_sub(1), i) } else { (i, (i + 1).min(tiles - 1)) };
                let wgt = if lo == hi { 0.0 } else { ((x as f32 - centre(lo)) / (centre(hi) - centre(lo))).clamp(0.0, 1.0) };
                (lo, hi, wgt)
            })
            .collect()
    };
    let (ax, ay) = (axis(w, nx), axis(h, ny));
    let mut v = Vec::with_capacity(w * h);
    for (y, &(y0, y1, wy)) in ay.iter().enumerate() {
        for (x, &(x0, x1, wx)) in ax.iter().enumerate() {
            let top = med[y0 * nx + x0] * (1.0 - wx) + med[y0 * nx + x1] * wx;
            let bottom = med[y1 * nx + x0] * (1.0 - wx) + med[y1 * nx + x1] * wx;
            v.push(pl.v[y * w + x] - (top * (1.0 - wy) + bottom * wy));
        }
    }
    Plane { w, h, v }
}

/// Otsu's threshold on a 256-bin histogram of `v`.
fn otsu(v: &[f32]) -> f64 {
    let mut hist = [0u64; 256];
    // `as` saturates (NaN → 0), so the clamp keeps the index in range.
    v.iter().for_each(|&x| hist[((x + 0.5) as i32).clamp(0, 255) as usize] += 1);
    let total: u64 = hist.iter().sum();
    let sum_all: f64 = hist.iter().enumerate().map(|(i, &c)| i as f64 * c as f64).sum();
    let (mut w0, mut sum0, mut best, mut best_t) = (0u64, 0.0, -1.0, 0.0);
    for (i, &c) in hist.iter().enumerate() {
        w0 += c;
        sum0 += i as f64 * c as f64;
        let w1 = total - w0;
        if w0 == 0 || w1 == 0 {
            continue;
        }
        let (m0, m1) = (sum0 / w0 as f64, (sum_all - sum0) / w1 as f64);
        let between = w0 as f64 * w1 as f64 * (m0 - m1) * (m0 - m1);
        if between > best {
            best = between;
            best_t = i as f64 + 0.5;
        }
    }
    best_t
}

/// A thresholded 8-connected blob.
struct Blob {
    area: usize,
    /// Centroid of the above-threshold excess.
    c: [f64; 2],
}

/// More blobs than this in one image is an error (a wrong threshold or polarity, not markers).
pub const MAX_BLOBS: usize = 20_000;

fn detect_plane(pl: &Plane, p: &TrackParams) -> Result<Detection> {
    let (background, _) = median_and_sigma(&pl.v);
    let flat = flatten(pl);
    let (_, noise) = median_and_sigma(&flat.v);
    // Automatic: on the flattened signal; given: on the raw one.
    let (mask, threshold) = match p.threshold {
        Some(t) => (pl, f64::from(signal(t as f32, p.polarity))),
        None => (&flat, otsu(&flat.v).max(5.0 * noise).max(1.0)),
    };
    let blobs = components(mask, threshold, p);
    if blobs.len() > MAX_BLOBS {
        bail!("{} blobs found, more than {MAX_BLOBS}: not markers (check the polarity, the threshold and the minimum area)", blobs.len());
    }
    let centres = blobs.iter().enumerate().map(|(i, b)| refine(&flat, &blobs, i, 0.0).unwrap_or(b.c)).collect();
    Ok(Detection { centres, background, noise, threshold })
}

/// Connected components (8-neighbours) of the pixels above `t`, filtered by area and border.
fn components(pl: &Plane, t: f64, p: &TrackParams) -> Vec<Blob> {
    let (w, h) = (pl.w, pl.h);
    let t = t as f32;
    let mut seen = vec![false; w * h];
    let mut stack = Vec::new();
    let mut out = Vec::new();
    for start in 0..w * h {
        if seen[start] || pl.v[start] <= t {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let (mut area, mut sw, mut sx, mut sy, mut border) = (0usize, 0.0f64, 0.0f64, 0.0f64, false);
        while let Some(k) = stack.pop() {
            let (x, y) = (k % w, k / w);
            let e = f64::from(pl.v[k] - t);
            area += 1;
            sw += e;
            sx += e * x as f64;
            sy += e * y as f64;
            border |= x == 0 || y == 0 || x + 1 == w || y + 1 == h;
            for (dx, dy) in [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
                let (nx, ny) = (x as isize + dx, y as isize + dy);
                if nx < 0 || ny < 0 || nx >= w as isize || ny >= h as isize {
                    continue;
                }
                let nk = ny as usize * w + nx as usize;
                if !seen[nk] && pl.v[nk] > t {
                    seen[nk] = true;
                    stack.push(nk);
                }
            }
        }
        if !border && (p.min_area_px..=p.max_area_px).contains(&area) && sw > 0.0 {
            out.push(Blob { area, c: [sx / sw, sy / sw] });
        }
    }
    out
}

/// The sub-pixel centre of blob `i`: a background-subtracted intensity-weighted centroid over a
/// soft-edged disc, re-centred three times. `None` when the window holds no positive signal or
/// the centre wanders farther than the window's radius from the blob's own centroid.
fn refine(pl: &Plane, blobs: &[Blob], i: usize, global_bg: f64) -> Option<[f64; 2]> {
    let b = &blobs[i];
    let r_eq = (b.area as f64 / std::f64::consts::PI).sqrt();
    let mut rw = r_eq + 2.0;
    for (j, o) in blobs.iter().enumerate() {
        if j != i {
            let d = ((o.c[0] - b.c[0]).powi(2) + (o.c[1] - b.c[1]).powi(2)).sqrt();
            let r_o = (o.area as f64 / std::f64::consts::PI).sqrt();
            rw = rw.min(d - r_o - 1.0);
        }
    }
    let rw = rw.max(r_eq + 0.5);
    let mut c = b.c;
    let mut ring = Vec::new();
    for _ in 0..3 {
        let reach = rw + 2.5;
        let x0 = (c[0] - reach).floor().max(0.0) as usize;
        let x1 = ((c[0] + reach).ceil().max(0.0) as usize).min(pl.w - 1);
        let y0 = (c[1] - reach).floor().max(0.0) as usize;
        let y1 = ((c[1] + reach).ceil().max(0.0) as usize).min(pl.h - 1);
        ring.clear();
        for y in y0..=y1 {
            for x in x0..=x1 {
                let r = ((x as f64 - c[0]).powi(2) + (y as f64 - c[1]).powi(2)).sqrt();
                if r > rw + 0.5 && r <= reach {
                    ring.push(pl.v[y * pl.w + x]);
                }
            }
        }
        let bg = if ring.len() >= 8 {
            ring.sort_unstable_by(f32::total_cmp);
            f64::from(ring[ring.len() / 2])
        } else {
            global_bg
        };
        let (mut sw, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (dx, dy) = (x as f64 - c[0], y as f64 - c[1]);
                let soft = (rw + 0.5 - (dx * dx + dy * dy).sqrt()).clamp(0.0, 1.0);
                if soft > 0.0 {
                    let e = soft * (f64::from(pl.v[y * pl.w + x]) - bg);
                    sw += e;
                    sx += e * dx;
                    sy += e * dy;
                }
            }
        }
        if sw <= 0.0 {
            return None;
        }
        let step = [sx / sw, sy / sw];
        c = [c[0] + step[0], c[1] + step[1]];
        if step[0].abs() + step[1].abs() < 1e-4 {
            break;
        }
    }
    // A centre that wandered off its blob (an odd, non-round blob) is not trusted.
    ((c[0] - b.c[0]).hypot(c[1] - b.c[1]) <= rw).then_some(c)
}

/// The sub-pixel centres (x right, y down, pixel centres at integer coordinates) of the markers
/// in one image, in raster order of their first pixel. An image with no markers gives an empty
/// list.
///
/// Errors: invalid parameters ([`TrackParams::validate`]), an empty image, more than
/// [`MAX_BLOBS`] blobs.
pub fn detect(img: &GrayImage, p: &TrackParams) -> Result<Vec<[f64; 2]>> {
    p.validate()?;
    if img.width() == 0 || img.height() == 0 {
        bail!("detect: the image is empty");
    }
    Ok(detect_plane(&Plane::from_gray8(img, p.polarity), p)?.centres)
}

/// Median distance from each point to its nearest other point (0 with fewer than two points).
fn median_nn_distance(pts: &[[f64; 2]]) -> f64 {
    if pts.len() < 2 {
        return 0.0;
    }
    let mut d: Vec<f64> = pts
        .iter()
        .enumerate()
        .map(|(i, a)| {
            pts.iter().enumerate().filter(|&(j, _)| j != i).map(|(_, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(f64::INFINITY, f64::min)
        })
        .collect();
    d.sort_unstable_by(f64::total_cmp);
    d[d.len() / 2]
}

/// The marker spacing: the median of all pairwise distances within ±25 % of the median
/// nearest-neighbour distance (every grid neighbour pair, not only each point's nearest, whose
/// minimum over several noisy neighbours would be biased low).
fn spacing(pts: &[[f64; 2]]) -> f64 {
    let nn = median_nn_distance(pts);
    let mut d: Vec<f64> = Vec::new();
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            let e = (a[0] - b[0]).hypot(a[1] - b[1]);
            if e > 0.75 * nn && e < 1.25 * nn {
                d.push(e);
            }
        }
    }
    if d.is_empty() {
        return nn;
    }
    d.sort_unstable_by(f64::total_cmp);
    d[d.len() / 2]
}

/// Orders points row-major from the top-left: sorted by y, a new row wherever consecutive y
/// values differ by more than half the median spacing, each row sorted by x.
fn row_major(mut pts: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    let gap = 0.5 * median_nn_distance(&pts);
    pts.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
    let mut out = Vec::with_capacity(pts.len());
    let mut row: Vec<[f64; 2]> = Vec::new();
    for q in pts {
        if let Some(last) = row.last()
            && q[1] - last[1] > gap
        {
            row.sort_by(|a, b| a[0].total_cmp(&b[0]));
            out.append(&mut row);
        }
        row.push(q);
    }
    row.sort_by(|a, b| a[0].total_cmp(&b[0]));
    out.append(&mut row);
    out
}

/// Incremental tracker: feed frames in time order with [`Tracker::push_image`] or
/// [`Tracker::push_png`], then [`Tracker::finish`]. Errors name the frame (its index in the order
/// pushed); callers add the file name.
pub struct Tracker {
    p: TrackParams,
    size: Option<(usize, usize)>,
    times: Vec<f64>,
    n: usize,
    pos: Vec<[f64; 2]>,
    det: Vec<bool>,
    /// Per marker: consecutive frames missed up to the last one.
    missing: Vec<usize>,
}

impl Tracker {
    /// A tracker with no frames yet. Errors: invalid parameters ([`TrackParams::validate`]).
    pub fn new(p: TrackParams) -> Result<Self> {
        p.validate()?;
        Ok(Self { p, size: None, times: Vec::new(), n: 0, pos: Vec::new(), det: Vec::new(), missing: Vec::new() })
    }

    /// The number of frames tracked so far.
    pub fn n_frames(&self) -> usize {
        self.times.len()
    }

    /// Tracks one 8-bit frame taken at `t_s`. See [`Tracker::push_png`] for the errors.
    pub fn push_image(&mut self, t_s: f64, img: &GrayImage) -> Result<()> {
        self.push_plane(t_s, Plane::from_gray8(img, self.p.polarity))
    }

    /// Decodes a PNG (8- or 16-bit, gray or colour: colour is converted to luma) and tracks it.
    ///
    /// Errors (each names the frame): bytes that are not a decodable PNG; an image of more than
    /// `max_image_pixels` pixels (a [`SizeLimit`], checked from the header before decoding); a time stamp that
    /// is not finite or not after the previous frame's; an image whose size differs from frame
    /// 0's; in frame 0, no markers found or a count other than `expected_markers`; more than
    /// [`MAX_BLOBS`] blobs in any frame; later, fewer than half
    /// the markers found near their predictions, or a marker missing for more than
    /// `max_missing_frames` consecutive frames. After an error the tracker is unchanged.
    pub fn push_png(&mut self, t_s: f64, png: &[u8]) -> Result<()> {
        let k = self.times.len();
        let (w, h) = png_dimensions(png).with_context(|| format!("frame {k}: not a decodable PNG image"))?;
        let pixels = u64::from(w) * u64::from(h);
        if pixels > self.p.max_image_pixels {
            return Err(anyhow::Error::new(SizeLimit {
                what: format!("frame {k} ({w} × {h} pixels)"),
                amount: pixels as f64,
                limit: self.p.max_image_pixels,
                unit: "pixels",
                hint: " (server flag --max-image-pixels)".to_owned(),
            }));
        }
        // The decoded image holds at most 8 bytes per pixel (16-bit RGBA), bounded by the check
        // above; the decoder's own buffers (rows, metadata chunks) are held to as much plus 1 MiB.
        let max_decoder_bytes = usize::try_from(pixels.saturating_mul(8).saturating_add(1 << 20)).unwrap_or(usize::MAX);
        let (w, h, levels) = decode_png_levels(png, max_decoder_bytes).with_context(|| format!("frame {k}: not a decodable PNG image"))?;
        self.push_plane(t_s, Plane::from_levels(w, h, levels, self.p.polarity))
    }

    fn push_plane(&mut self, t: f64, pl: Plane) -> Result<()> {
        let k = self.times.len();
        if !t.is_finite() {
            bail!("frame {k}: time stamp {t} is not a finite number");
        }
        if let Some(&prev) = self.times.last()
            && t <= prev
        {
            bail!("frame {k}: time stamp {t} s does not come after frame {}'s {prev} s (time stamps must increase)", k - 1);
        }
        if pl.w == 0 || pl.h == 0 {
            bail!("frame {k}: the image is empty");
        }
        match self.size {
            Some((w, h)) if (w, h) != (pl.w, pl.h) => {
                bail!("frame {k}: the image is {}×{} pixels but frame 0 is {w}×{h}", pl.w, pl.h)
            }
            _ => {}
        }
        let found = detect_plane(&pl, &self.p).with_context(|| format!("frame {k}"))?;
        if k == 0 {
            if found.centres.is_empty() {
                let why = match self.p.threshold {
                    Some(t) => format!("threshold {t} gray levels"),
                    None => format!(
                        "automatic threshold {:.1} gray levels from the local background, which is {:.1} ± {:.1} overall",
                        found.threshold,
                        signal(found.background as f32, self.p.polarity),
                        found.noise
                    ),
                };
                bail!(
                    "frame 0: no {} markers found ({why}; check the polarity, the threshold and the area limits {}–{} px)",
                    match self.p.polarity {
                        Polarity::Dark => "dark",
                        Polarity::Bright => "bright",
                    },
                    self.p.min_area_px,
                    self.p.max_area_px
                );
            }
            if let Some(e) = self.p.expected_markers
                && e != found.centres.len()
            {
                bail!(
                    "frame 0: found {} markers but {e} are expected (the marker count differs; adjust the threshold or the area limits)",
                    found.centres.len()
                );
            }
            if matches!(self.p.scale, Scale::MarkerSpacing { .. }) && found.centres.len() < 2 {
                bail!("frame 0: the marker-spacing scale needs at least 2 markers, found 1");
            }
            let ordered = row_major(found.centres);
            self.n = ordered.len();
            self.pos = ordered;
            self.det = vec![true; self.n];
            self.missing = vec![0; self.n];
            self.size = Some((pl.w, pl.h));
            self.times.push(t);
            return Ok(());
        }
        let n = self.n;
        let last = &self.pos[(k - 1) * n..k * n];
        let pred: Vec<[f64; 2]> = if k >= 2 {
            let before = &self.pos[(k - 2) * n..(k - 1) * n];
            let s = (t - self.times[k - 1]) / (self.times[k - 1] - self.times[k - 2]);
            last.iter().zip(before).map(|(a, b)| [a[0] + s * (a[0] - b[0]), a[1] + s * (a[1] - b[1])]).collect()
        } else {
            last.to_vec()
        };
        let assign = mutual_nearest(&pred, &found.centres, self.p.max_jump_px);
        let matched = assign.iter().filter(|a| a.is_some()).count();
        if n >= 4 && 2 * matched < n {
            bail!(
                "frame {k}: only {matched} of {n} markers found within {} px of their predicted positions \
                 (a jump larger than the max jump, a change of lighting or a different scene?)",
                self.p.max_jump_px
            );
        }
        let mut missing = self.missing.clone();
        for (m, a) in assign.iter().enumerate() {
            match a {
                Some(_) => missing[m] = 0,
                None => {
                    missing[m] += 1;
                    if missing[m] > self.p.max_missing_frames {
                        let p0 = self.pos[m];
                        bail!(
                            "frame {k}: marker {m} (at ({:.1}, {:.1}) px in frame 0) not found in frames {}–{k}, more than {} \
                             consecutive frames: the marker count changed ({} of {n} found in this frame)",
                            p0[0],
                            p0[1],
                            k + 1 - missing[m],
                            self.p.max_missing_frames,
                            matched
                        );
                    }
                }
            }
        }
        self.missing = missing;
        for (m, a) in assign.iter().enumerate() {
            match a {
                Some(d) => {
                    self.pos.push(found.centres[*d]);
                    self.det.push(true);
                }
                None => {
                    self.pos.push(pred[m]);
                    self.det.push(false);
                }
            }
        }
        self.times.push(t);
        Ok(())
    }

    /// The tracks, with metres from the scale. Errors: no frames were pushed; a marker-spacing
    /// scale whose frame-0 markers coincide (no spacing to measure).
    pub fn finish(self) -> Result<MarkerTracks> {
        let Some((_, h)) = self.size else { bail!("track: no frames") };
        let (s, origin_px, origin_m) = resolve_scale(&self.p.scale, &self.pos[..self.n], h as f64);
        if !(s.is_finite() && s > 0.0) {
            bail!("frame 0: the markers have no measurable spacing, so the marker-spacing scale is undefined");
        }
        let positions_m =
            self.pos.iter().map(|q| [origin_m[0] + (q[0] - origin_px[0]) * s, origin_m[1] - (q[1] - origin_px[1]) * s]).collect();
        Ok(MarkerTracks { times_s: self.times, n_markers: self.n, positions_px: self.pos, positions_m, detected: self.det })
    }
}

/// `(m_per_px, origin_px, origin_m)` of `scale` given the frame-0 markers and the image height.
fn resolve_scale(scale: &Scale, frame0: &[[f64; 2]], height_px: f64) -> (f64, [f64; 2], [f64; 2]) {
    match scale {
        Scale::MetresPerPixel { m_per_px, origin_px, origin_m } => (*m_per_px, *origin_px, *origin_m),
        Scale::MarkerSpacing { spacing_m, origin_m } => {
            let s = spacing_m / spacing(frame0);
            let corner = |q: &[f64; 2]| q[0].hypot(height_px - q[1]);
            let origin_px = frame0.iter().copied().min_by(|a, b| corner(a).total_cmp(&corner(b))).unwrap_or([0.0, 0.0]);
            (s, origin_px, *origin_m)
        }
    }
}

/// Pairs predictions with detections that are each other's nearest within `gate`, repeating on
/// the unpaired ones until no pair forms. Returns, per prediction, the index of its detection.
fn mutual_nearest(pred: &[[f64; 2]], det: &[[f64; 2]], gate: f64) -> Vec<Option<usize>> {
    let mut of_pred: Vec<Option<usize>> = vec![None; pred.len()];
    let mut taken = vec![false; det.len()];
    let d2 = |a: &[f64; 2], b: &[f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
    let gate2 = gate * gate;
    loop {
        let mut nearest_pred: Vec<Option<(usize, f64)>> = vec![None; det.len()];
        for (i, a) in pred.iter().enumerate().filter(|(i, _)| of_pred[*i].is_none()) {
            for (j, b) in det.iter().enumerate().filter(|(j, _)| !taken[*j]) {
                let d = d2(a, b);
                if d <= gate2 && nearest_pred[j].is_none_or(|(_, e)| d < e) {
                    nearest_pred[j] = Some((i, d));
                }
            }
        }
        let mut paired = false;
        for (i, a) in pred.iter().enumerate() {
            if of_pred[i].is_some() {
                continue;
            }
            let best = det
                .iter()
                .enumerate()
                .filter(|(j, _)| !taken[*j])
                .map(|(j, b)| (j, d2(a, b)))
                .filter(|&(_, d)| d <= gate2)
                .min_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((j, _)) = best
                && nearest_pred[j].is_some_and(|(ii, _)| ii == i)
            {
                of_pred[i] = Some(j);
                taken[j] = true;
                paired = true;
            }
        }
        if !paired {
            return of_pred;
        }
    }
}

/// Tracks a sequence of 8-bit frames `(t_s, image)`; `progress(done, total)` is called after each
/// frame (`Break` stops the call with [`crate::Cancelled`]). Errors: as [`Tracker::push_png`] (naming the frame), or an empty sequence.
pub fn track_frames(frames: &[(f64, GrayImage)], p: &TrackParams, progress: crate::Progress<'_>) -> Result<MarkerTracks> {
    if frames.is_empty() {
        bail!("track: no frames");
    }
    let mut tr = Tracker::new(p.clone())?;
    for (i, (t, img)) in frames.iter().enumerate() {
        tr.push_image(*t, img)?;
        crate::report(progress, i + 1, frames.len())?;
    }
    tr.finish()
}

/// Tracks a sequence of PNG-encoded frames `(t_s, png bytes)`, decoding one at a time;
/// `progress(done, total)` is called after each frame (`Break`: [`crate::Cancelled`]). Errors: as [`Tracker::push_png`] (naming
/// the frame), or an empty sequence.
pub fn track_png_bytes(frames: &[(f64, &[u8])], p: &TrackParams, progress: crate::Progress<'_>) -> Result<MarkerTracks> {
    if frames.is_empty() {
        bail!("track: no frames");
    }
    let mut tr = Tracker::new(p.clone())?;
    for (i, (t, png)) in frames.iter().enumerate() {
        tr.push_png(*t, png)?;
        crate::report(progress, i + 1, frames.len())?;
    }
    tr.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    #[cfg(feature = "synthetic")]
    use crate::render::{RenderParams, render_frame};
    #[cfg(feature = "synthetic")]
    use rand::{Rng, SeedableRng, rngs::SmallRng};

    fn params() -> TrackParams {
        TrackParams::new(Polarity::Dark, Scale::MetresPerPixel { m_per_px: 1e-4, origin_px: [0.0, 0.0], origin_m: [0.0, 0.0] })
    }

    /// Issue 13: a small PNG whose header announces 65535 × 1000 pixels is rejected from its
    /// header, before the decoder allocates half a gigabyte for it.
    #[test]
    fn issue_13_png_announcing_a_huge_frame_is_rejected_before_decoding() {
        let mut png = GrayImage::new(8, 8).to_png().unwrap();
        // IHDR: bytes 8..12 length, 12..16 "IHDR", 16..20 width, 20..24 height, 29..33 CRC.
        assert_eq!(&png[12..16], b"IHDR");
        png[16..20].copy_from_slice(&65_535u32.to_be_bytes());
        png[20..24].copy_from_slice(&1_000u32.to_be_bytes());
        let crc = crc32fast::hash(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        let e = Tracker::new(params()).unwrap().push_png(0.0, &png).unwrap_err();
        let size = e.downcast_ref::<SizeLimit>().unwrap_or_else(|| panic!("not a size limit: {e:#}"));
        assert_eq!((size.amount, size.limit), (65_535_000.0, DEFAULT_MAX_IMAGE_PIXELS), "{e:#}");
        assert!(e.to_string().starts_with("frame 0 (65535 × 1000 pixels)"), "{e:#}");
    }

    #[cfg(feature = "synthetic")]
    /// A `cols × rows` grid with spacing `sp` px starting at `(x0, y0)`, jittered by up to ±0.5 px.
    fn grid(rng: &mut SmallRng, cols: usize, rows: usize, x0: f64, y0: f64, sp: f64) -> Vec<[f64; 2]> {
        let mut v = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                v.push([x0 + c as f64 * sp + rng.random_range(-0.5..0.5), y0 + r as f64 * sp + rng.random_range(-0.5..0.5)]);
            }
        }
        v
    }

    #[cfg(feature = "synthetic")]
    /// RMS distance between detections and the truth, each detection paired with its nearest truth.
    fn rms_vs_truth(found: &[[f64; 2]], truth: &[[f64; 2]]) -> f64 {
        assert_eq!(found.len(), truth.len());
        let s: f64 =
            found.iter().map(|f| truth.iter().map(|t| (f[0] - t[0]).powi(2) + (f[1] - t[1]).powi(2)).fold(f64::INFINITY, f64::min)).sum();
        (s / found.len() as f64).sqrt()
    }

    #[test]
    fn issue_13_an_image_over_the_pixel_limit_is_refused_from_its_header() {
        let png = GrayImage::new(100, 80).to_png().unwrap();
        let p = TrackParams { max_image_pixels: 7999, ..params() };
        let e = track_png_bytes(&[(0.0, &png)], &p, &mut crate::no_progress).unwrap_err();
        let size = e.downcast_ref::<SizeLimit>().unwrap_or_else(|| panic!("not a size limit: {e:#}"));
        assert_eq!((size.amount, size.limit), (8000.0, 7999));
        assert!(e.to_string().contains("frame 0 (100 × 80 pixels)"), "{e}");
    }

    #[cfg(feature = "synthetic")]
    #[test]
    fn issue_9_detected_centroids_within_a_tenth_of_a_pixel_rms_with_noise() {
        let mut rng = SmallRng::seed_from_u64(9);
        for (noise, blur, polarity) in [(3.0, 1.0, Polarity::Dark), (5.0, 1.0, Polarity::Dark), (4.0, 1.5, Polarity::Bright)] {
            let truth = grid(&mut rng, 10, 8, 30.0, 30.0, 24.0);
            let (background, contrast) = if polarity == Polarity::Dark { (200.0, 120.0) } else { (40.0, 150.0) };
            let rp = RenderParams {
                width_px: 300,
                height_px: 240,
                noise_sigma: noise,
                blur_sigma_px: blur,
                polarity,
                background,
                contrast,
                ..Default::default()
            };
            let img = render_frame(&truth, &rp, 1);
            let found = detect(&img, &TrackParams { polarity, ..params() }).unwrap();
            let rms = rms_vs_truth(&found, &truth);
            assert!(rms < 0.1, "noise {noise} blur {blur}: RMS {rms} px");
        }
    }

    #[cfg(feature = "synthetic")]
    #[test]
    fn a_missing_dot_is_filled_in_and_its_track_stays_on_the_right_marker() {
        let mut rng = SmallRng::seed_from_u64(1);
        let base = grid(&mut rng, 6, 5, 20.0, 20.0, 20.0);
        let rp = RenderParams { width_px: 160, height_px: 130, noise_sigma: 3.0, ..Default::default() };
        let truth: Vec<Vec<[f64; 2]>> =
            (0..5).map(|f| base.iter().map(|q| [q[0] + 1.5 * f as f64 + 0.02 * q[1], q[1] - 0.8 * f as f64]).collect()).collect();
        let frames: Vec<(f64, GrayImage)> = truth
            .iter()
            .enumerate()
            .map(|(f, pts)| {
                // Marker 7 is missing in frame 2; a spurious small blob appears in frame 3.
                let mut drawn: Vec<[f64; 2]> = pts.iter().enumerate().filter(|&(m, _)| !(f == 2 && m == 7)).map(|(_, q)| *q).collect();
                if f == 3 {
                    drawn.push([150.0, 120.0]);
                }
                (0.1 * f as f64, render_frame(&drawn, &rp, f as u64))
            })
            .collect();
        let mut calls = Vec::new();
        let tr = track_frames(&frames, &params(), &mut |d, n| {
            calls.push((d, n));
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
        assert_eq!(calls.last(), Some(&(5, 5)));
        assert_eq!(tr.n_markers, 30);
        for (f, pts) in truth.iter().enumerate() {
            for (m, t) in pts.iter().enumerate() {
                let q = tr.positions_px[f * 30 + m];
                let err = (q[0] - t[0]).hypot(q[1] - t[1]);
                let filled = f == 2 && m == 7;
                assert_eq!(tr.detected[f * 30 + m], !filled, "frame {f} marker {m}");
                assert!(err < if filled { 0.3 } else { 0.15 }, "frame {f} marker {m}: error {err} px");
            }
        }
    }

    #[cfg(feature = "synthetic")]
    #[test]
    fn a_marker_that_disappears_is_an_error_naming_the_frame() {
        let mut rng = SmallRng::seed_from_u64(2);
        let base = grid(&mut rng, 4, 4, 20.0, 20.0, 20.0);
        let rp = RenderParams { width_px: 100, height_px: 100, ..Default::default() };
        let frames: Vec<(f64, GrayImage)> = (0..6)
            .map(|f| {
                let pts: Vec<[f64; 2]> = base.iter().enumerate().filter(|&(m, _)| f < 2 || m != 5).map(|(_, q)| *q).collect();
                (f as f64, render_frame(&pts, &rp, f as u64))
            })
            .collect();
        let p = TrackParams { max_missing_frames: 1, ..params() };
        let e = format!("{:#}", track_frames(&frames, &p, &mut crate::no_progress).unwrap_err());
        assert!(e.contains("frame 3: marker 5") && e.contains("frames 2–3") && e.contains("marker count changed"), "{e}");
        let p = TrackParams { expected_markers: Some(17), ..params() };
        let e = format!("{:#}", track_frames(&frames, &p, &mut crate::no_progress).unwrap_err());
        assert!(e.contains("frame 0: found 16 markers but 17 are expected"), "{e}");
    }

    #[cfg(feature = "synthetic")]
    #[test]
    fn bad_inputs_give_errors_naming_the_frame() {
        let rp = RenderParams { width_px: 60, height_px: 60, ..Default::default() };
        let img = render_frame(&[[30.0, 30.0]], &rp, 0);
        let small = render_frame(&[[20.0, 20.0]], &RenderParams { width_px: 50, ..rp.clone() }, 0);
        let p = params();
        let e = track_frames(&[(0.0, img.clone()), (1.0, small)], &p, &mut crate::no_progress).unwrap_err().to_string();
        assert!(e.contains("frame 1: the image is 50×60 pixels but frame 0 is 60×60"), "{e}");
        let e = track_frames(&[(0.0, img.clone()), (0.0, img.clone())], &p, &mut crate::no_progress).unwrap_err().to_string();
        assert!(e.contains("frame 1: time stamp 0 s does not come after"), "{e}");
        let blank = render_frame(&[], &rp, 0);
        let e = track_frames(&[(0.0, blank)], &p, &mut crate::no_progress).unwrap_err().to_string();
        assert!(e.contains("frame 0: no dark markers found (automatic threshold"), "{e}");
        let e = track_frames(&[(0.0, img.clone())], &TrackParams { polarity: Polarity::Bright, ..p.clone() }, &mut crate::no_progress)
            .unwrap_err()
            .to_string();
        assert!(e.contains("frame 0: no bright markers found"), "{e}");
        let e = format!("{:#}", track_png_bytes(&[(0.0, b"not a png".as_slice())], &p, &mut crate::no_progress).unwrap_err());
        assert!(e.contains("frame 0: not a decodable PNG"), "{e}");
        assert!(track_frames(&[], &p, &mut crate::no_progress).is_err());
        // A speckle of isolated dark pixels: 40 000 one-pixel blobs, none of them markers.
        let speckle = GrayImage::from_fn(402, 402, |x, y| if x % 2 == 1 && y % 2 == 1 { 0 } else { 200 });
        let loose = TrackParams { min_area_px: 1, ..p.clone() };
        let e = track_frames(&[(0.0, speckle)], &loose, &mut crate::no_progress).err().map(|e| format!("{e:#}")).unwrap_or_default();
        assert!(e.contains("frame 0:") && e.contains("40000 blobs found, more than 20000"), "{e}");
        let e = TrackParams { max_jump_px: -1.0, ..p }.validate().unwrap_err().to_string();
        assert!(e.contains("max jump"), "{e}");
    }

    #[cfg(feature = "synthetic")]
    #[test]
    fn marker_spacing_scale_recovers_metres_and_png_bytes_track_like_images() {
        // A 5 × 4 grid at 25 px spacing, no jitter; 1 px = 0.4 mm when the spacing is 10 mm.
        let base: Vec<[f64; 2]> = (0..4).flat_map(|r| (0..5).map(move |c| [20.3 + 25.0 * c as f64, 15.6 + 25.0 * r as f64])).collect();
        let rp = RenderParams { width_px: 140, height_px: 110, noise_sigma: 2.0, ..Default::default() };
        let moved: Vec<[f64; 2]> = base.iter().map(|q| [q[0] + 2.5, q[1]]).collect();
        let rendered: Vec<GrayImage> = [&base, &moved].iter().enumerate().map(|(f, pts)| render_frame(pts, &rp, f as u64)).collect();
        let pngs: Vec<Vec<u8>> = rendered.iter().map(|img| img.to_png().unwrap()).collect();
        let p = TrackParams {
            expected_markers: Some(20),
            ..TrackParams::new(Polarity::Dark, Scale::MarkerSpacing { spacing_m: 0.01, origin_m: [0.005, 0.002] })
        };
        let frames: Vec<(f64, &[u8])> = vec![(0.0, &pngs[0]), (0.04, &pngs[1])];
        let tr = track_png_bytes(&frames, &p, &mut crate::no_progress).unwrap();
        // Row-major from the top-left: marker 15 is the bottom-left one, the origin.
        let o = tr.position_m(0, 15);
        assert!((o[0] - 0.005).abs() < 1e-9 && (o[1] - 0.002).abs() < 1e-9, "{o:?}");
        let top_right = tr.position_m(0, 4);
        assert!((top_right[0] - 0.045).abs() < 1e-4 && (top_right[1] - 0.032).abs() < 1e-4, "{top_right:?}");
        for m in 0..20 {
            let d = tr.displacement_m(1, m);
            assert!((d[0] - 0.001).abs() < 5e-5 && d[1].abs() < 5e-5, "marker {m}: {d:?}");
        }
        // The same frames as images give the same tracks.
        let imgs: Vec<(f64, GrayImage)> = frames.iter().zip(rendered).map(|((t, _), img)| (*t, img)).collect();
        assert_eq!(track_frames(&imgs, &p, &mut crate::no_progress).unwrap(), tr);
    }

    #[cfg(feature = "synthetic")]
    /// The figures of the report: RMS centroid error by noise and blur (dots of radius 4 px,
    /// contrast 120, 5 images of 80 dots each), and the time to track a 640 × 480 frame with 100
    /// markers (median of 5 runs over 10 frames). Run with
    /// `cargo test --release -p needlesim-identify --features synthetic --lib track::tests::figures -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn figures() {
        let mut rng = SmallRng::seed_from_u64(99);
        println!("| noise σ (gray levels) | blur σ (px) | RMS error (px) |");
        println!("|---|---|---|");
        for (noise, blur) in [(0.0, 1.0), (2.0, 1.0), (4.0, 1.0), (8.0, 1.0), (4.0, 0.5), (4.0, 2.0)] {
            let (mut s2, mut n) = (0.0, 0usize);
            for k in 0..5 {
                let truth = grid(&mut rng, 10, 8, 30.0, 30.0, 24.0);
                let rp = RenderParams { width_px: 300, height_px: 240, noise_sigma: noise, blur_sigma_px: blur, ..Default::default() };
                let found = detect(&render_frame(&truth, &rp, k), &params()).unwrap();
                s2 += rms_vs_truth(&found, &truth).powi(2) * found.len() as f64;
                n += found.len();
            }
            println!("| {noise} | {blur} | {:.4} |", (s2 / n as f64).sqrt());
        }
        let base = grid(&mut rng, 10, 10, 50.0, 30.0, 45.0);
        let rp = RenderParams { noise_sigma: 4.0, ..Default::default() };
        let frames: Vec<(f64, GrayImage)> = (0..10)
            .map(|f| {
                let pts: Vec<[f64; 2]> = base.iter().map(|q| [q[0] + 0.7 * f as f64, q[1] + 0.002 * f as f64 * q[0]]).collect();
                (f as f64 / 30.0, render_frame(&pts, &rp, f as u64))
            })
            .collect();
        let pngs: Vec<(f64, Vec<u8>)> = frames.iter().map(|(t, img)| (*t, img.to_png().unwrap())).collect();
        let png_refs: Vec<(f64, &[u8])> = pngs.iter().map(|(t, b)| (*t, b.as_slice())).collect();
        let median_ms = |f: &mut dyn FnMut()| {
            let mut v: Vec<f64> = (0..5)
                .map(|_| {
                    let t0 = std::time::Instant::now();
                    f();
                    t0.elapsed().as_secs_f64() * 1e3 / frames.len() as f64
                })
                .collect();
            v.sort_by(f64::total_cmp);
            v[2]
        };
        let p = TrackParams { expected_markers: Some(100), ..params() };
        let images = median_ms(&mut || assert_eq!(track_frames(&frames, &p, &mut crate::no_progress).unwrap().n_markers, 100));
        let decoded = median_ms(&mut || assert_eq!(track_png_bytes(&png_refs, &p, &mut crate::no_progress).unwrap().n_markers, 100));
        println!(
            "640×480, 100 markers: {images:.2} ms per frame from images, {decoded:.2} ms per frame from PNG bytes (decoding included)"
        );
    }

    #[cfg(feature = "synthetic")]
    #[test]
    fn uneven_lighting_is_flattened_before_thresholding() {
        // The background falls by 90 gray levels across the image, more than the dots' contrast of
        // 80: a single global threshold cannot separate dots from background.
        let mut rng = SmallRng::seed_from_u64(5);
        let truth = grid(&mut rng, 10, 8, 30.0, 30.0, 24.0);
        let rp = RenderParams { width_px: 300, height_px: 240, noise_sigma: 4.0, contrast: 80.0, ..Default::default() };
        let mut img = render_frame(&truth, &rp, 1);
        for (i, v) in img.as_mut_raw().iter_mut().enumerate() {
            let (x, y) = ((i % 300) as f64, (i / 300) as f64);
            let g = 70.0 * (x / 300.0) + 20.0 * (y / 240.0);
            *v = (f64::from(*v) - g).round().clamp(0.0, 255.0) as u8;
        }
        let found = detect(&img, &params()).unwrap();
        assert_eq!(found.len(), truth.len());
        let rms = rms_vs_truth(&found, &truth);
        assert!(rms < 0.1, "RMS {rms} px");
    }

    #[test]
    fn rows_are_numbered_from_the_top_left_even_when_tilted() {
        let pts: Vec<[f64; 2]> = (0..3).flat_map(|r| (0..4).map(move |c| [10.0 * c as f64, 10.0 * r as f64 + 0.8 * c as f64])).collect();
        let mut shuffled = pts.clone();
        shuffled.reverse();
        assert_eq!(row_major(shuffled), pts);
    }
}
