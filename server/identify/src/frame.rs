//! Grayscale frames and their PNG files: [`GrayImage`] (8-bit, row-major), the header read that
//! gives an image's size before any pixel is decoded ([`png_dimensions`]), and decoding into gray
//! levels. Encoding (for the synthetic images) is built with the `synthetic` feature and in tests.
//!
//! Decoding accepts what a camera or an image tool writes: gray or colour, with or without alpha,
//! any bit depth, palettes, interlacing (the `png` crate's `EXPAND` transformation); the first
//! frame of an animated PNG. Gray levels are on the 8-bit scale 0–255 whatever the bit depth
//! (16-bit samples divided by 257). Colour becomes luma, sRGB's Y = (2126 R + 7152 G + 722 B) /
//! 10000 in integer arithmetic at the sample's bit depth; alpha is ignored.

use std::io::Cursor;

/// An 8-bit grayscale image, row-major from the top-left pixel.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GrayImage {
    width_px: u32,
    height_px: u32,
    pixels: Vec<u8>,
}

impl GrayImage {
    /// A black image of `width_px × height_px`.
    pub fn new(width_px: u32, height_px: u32) -> Self {
        Self { width_px, height_px, pixels: vec![0; width_px as usize * height_px as usize] }
    }

    /// The image whose pixel `(x, y)` is `f(x, y)`.
    pub fn from_fn(width_px: u32, height_px: u32, mut f: impl FnMut(u32, u32) -> u8) -> Self {
        let pixels = (0..height_px).flat_map(|y| (0..width_px).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect();
        Self { width_px, height_px, pixels }
    }

    /// An image of the given pixels (row-major); `None` when their number is not `width_px × height_px`.
    pub fn from_raw(width_px: u32, height_px: u32, pixels: Vec<u8>) -> Option<Self> {
        (pixels.len() == width_px as usize * height_px as usize).then_some(Self { width_px, height_px, pixels })
    }

    /// Width, pixels.
    pub fn width(&self) -> u32 {
        self.width_px
    }

    /// Height, pixels.
    pub fn height(&self) -> u32 {
        self.height_px
    }

    /// The pixels, row-major.
    pub fn as_raw(&self) -> &[u8] {
        &self.pixels
    }

    /// The pixels, row-major, to modify.
    pub fn as_mut_raw(&mut self) -> &mut [u8] {
        &mut self.pixels
    }

    /// The image as an 8-bit grayscale PNG.
    #[cfg(any(test, feature = "synthetic"))]
    pub fn to_png(&self) -> Result<Vec<u8>, png::EncodingError> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width_px, self.height_px);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&self.pixels)?;
        writer.finish()?;
        Ok(out)
    }
}

/// The width and height of a PNG image in pixels, from its header (the signature and the `IHDR`
/// chunk, checksum included); nothing else is read. Errors: bytes that do not start as a PNG.
pub fn png_dimensions(png: &[u8]) -> Result<(u32, u32), png::DecodingError> {
    let mut decoder = png::Decoder::new(Cursor::new(png));
    let info = decoder.read_header_info()?;
    Ok((info.width, info.height))
}

/// Decodes a PNG into gray levels on the 8-bit scale (see the module documentation), row-major;
/// returns `(width_px, height_px, levels)`. The decoder's own buffers (rows, metadata chunks) are
/// held to `max_decoder_bytes`; the caller bounds the image itself from [`png_dimensions`] first
/// (its pixel buffer takes at most 8 bytes per pixel, 16-bit RGBA).
pub fn decode_png_levels(png: &[u8], max_decoder_bytes: usize) -> Result<(usize, usize, Vec<f32>), png::DecodingError> {
    let mut decoder = png::Decoder::new_with_limits(Cursor::new(png), png::Limits { bytes: max_decoder_bytes });
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info()?;
    let size = reader.output_buffer_size().ok_or(png::DecodingError::LimitsExceeded)?;
    let mut buf = vec![0u8; size];
    let out = reader.next_frame(&mut buf)?;
    buf.truncate(out.buffer_size());
    let (w, h) = (out.width as usize, out.height as usize);
    if w == 0 || h == 0 {
        return Ok((w, h, Vec::new()));
    }
    let sixteen = out.bit_depth == png::BitDepth::Sixteen;
    let channels = out.color_type.samples();
    let sample_bytes = if sixteen { 2 } else { 1 };
    let line = out.line_size;
    let mut levels = Vec::with_capacity(w * h);
    for row in buf.chunks_exact(line).take(h) {
        for px in row[..w * channels * sample_bytes].chunks_exact(channels * sample_bytes) {
            let sample =
                |i: usize| -> u32 { if sixteen { u32::from(u16::from_be_bytes([px[2 * i], px[2 * i + 1]])) } else { u32::from(px[i]) } };
            let value = match out.color_type {
                png::ColorType::Grayscale | png::ColorType::GrayscaleAlpha => sample(0),
                // EXPAND turns palettes into RGB(A); Indexed does not come out.
                _ => (2126 * sample(0) + 7152 * sample(1) + 722 * sample(2)) / 10_000,
            };
            levels.push(if sixteen { value as f32 / 257.0 } else { value as f32 });
        }
    }
    if levels.len() != w * h {
        return Err(png::DecodingError::LimitsExceeded);
    }
    Ok((w, h, levels))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PNG of `w × h` pixels of the given colour type and depth with raw `data`.
    fn encode(w: u32, h: u32, color: png::ColorType, depth: png::BitDepth, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut e = png::Encoder::new(&mut out, w, h);
        e.set_color(color);
        e.set_depth(depth);
        let mut wr = e.write_header().unwrap();
        wr.write_image_data(data).unwrap();
        wr.finish().unwrap();
        out
    }

    #[test]
    fn gray_colour_and_sixteen_bit_pngs_decode_to_the_same_levels() {
        let img = GrayImage::from_fn(5, 3, |x, y| (40 * x + 7 * y) as u8);
        let png8 = img.to_png().unwrap();
        assert_eq!(png_dimensions(&png8).unwrap(), (5, 3));
        let (w, h, v) = decode_png_levels(&png8, 1 << 20).unwrap();
        assert_eq!((w, h), (5, 3));
        let want: Vec<f32> = img.as_raw().iter().map(|&x| f32::from(x)).collect();
        assert_eq!(v, want);
        let rgb: Vec<u8> = img.as_raw().iter().flat_map(|&x| [x, x, x]).collect();
        let (_, _, v) = decode_png_levels(&encode(5, 3, png::ColorType::Rgb, png::BitDepth::Eight, &rgb), 1 << 20).unwrap();
        assert_eq!(v, want);
        let g16: Vec<u8> = img.as_raw().iter().flat_map(|&x| (u16::from(x) * 257).to_be_bytes()).collect();
        let (_, _, v) = decode_png_levels(&encode(5, 3, png::ColorType::Grayscale, png::BitDepth::Sixteen, &g16), 1 << 20).unwrap();
        assert_eq!(v, want);
        let rgba16: Vec<u8> =
            img.as_raw().iter().flat_map(|&x| [x, x, x, 255].into_iter().flat_map(|c| (u16::from(c) * 257).to_be_bytes())).collect();
        let (_, _, v) = decode_png_levels(&encode(5, 3, png::ColorType::Rgba, png::BitDepth::Sixteen, &rgba16), 1 << 20).unwrap();
        assert_eq!(v, want);
        assert!(png_dimensions(b"not a png").is_err());
    }
}
