//! Colours: the plain surface colour, a categorical palette (distinct colours for blocks and
//! components), the defect colours, and shading.

/// Background.
pub(crate) const BACKGROUND: u32 = 0xFF_FF_FF;
/// Text.
pub(crate) const INK: u32 = 0x20_20_20;
/// Plain surfaces.
pub(crate) const PLAIN: u32 = 0xB4_C8_DC;
/// Surfaces under defects (light, so the markers stand out).
pub(crate) const MUTED: u32 = 0xD8_D8_D8;
/// Wireframe.
pub(crate) const WIRE: u32 = 0x30_30_30;
/// Lines (1-cells) and dots (0-cells) in plain colouring.
pub(crate) const LINE: u32 = 0x1F_3A_93;
/// Faces opened by the clipping plane in boundary colouring.
pub(crate) const EXPOSED: u32 = 0xF2_B8_5A;
/// Marker outline.
pub(crate) const OUTLINE: u32 = 0x00_00_00;

/// Non-manifold vertices.
pub(crate) const NM_VERTEX: u32 = 0xFF_00_80;
/// Non-manifold edges.
pub(crate) const NM_EDGE: u32 = 0xE0_00_00;
/// Faces in more than two cells.
pub(crate) const NM_FACE: u32 = 0xC0_00_FF;
/// Boundary edges of a surface.
pub(crate) const BOUNDARY: u32 = 0xFF_8C_00;
/// Inverted or flat cells.
pub(crate) const INVERTED: u32 = 0x00_B4_FF;

fn hsv(h: f64, s: f64, v: f64) -> u32 {
    let h = (h.rem_euclid(1.0)) * 6.0;
    let i = h.floor();
    let f = h - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let (r, g, b) = match i as u32 % 6 {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    let c = |x: f64| (x * 255.0).round().clamp(0.0, 255.0) as u32;
    (c(r) << 16) | (c(g) << 8) | c(b)
}

/// The `i`-th categorical colour: hues by the golden angle, three saturation/value levels;
/// neighbours in `i` are far apart, and the first several hundred are distinct.
pub(crate) fn categorical(i: u32) -> u32 {
    const PHI: f64 = 0.618_033_988_749_895;
    let h = f64::from(i) * PHI;
    let level = (i / 7) % 3;
    let (s, v) = match level {
        0 => (0.55, 0.95),
        1 => (0.75, 0.80),
        _ => (0.40, 0.70),
    };
    // the low two bits of each channel carry i mod 64, so that near hues stay distinct
    let c = hsv(h + f64::from(i / 21) * 0.013, s, v) & !0x03_03_03;
    c | ((i & 3) << 16) | (((i >> 2) & 3) << 8) | ((i >> 4) & 3)
}

/// A blue-to-yellow colour ramp (viridis-like) at `t` in 0..=1, for fields.
pub(crate) fn ramp(t: f64) -> u32 {
    // a few viridis stops, interpolated linearly
    const STOPS: [(f64, f64, f64); 5] = [
        (0.267, 0.005, 0.329),
        (0.230, 0.322, 0.546),
        (0.128, 0.567, 0.551),
        (0.369, 0.789, 0.383),
        (0.993, 0.906, 0.144),
    ];
    let x = t.clamp(0.0, 1.0) * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let c = |p: f64, q: f64| ((p + (q - p) * f) * 255.0).round().clamp(0.0, 255.0) as u32;
    (c(a.0, b.0) << 16) | (c(a.1, b.1) << 8) | c(a.2, b.2)
}

/// `c` with each channel multiplied by `f` (0..=1).
pub(crate) fn shade(c: u32, f: f32) -> u32 {
    let f = f.clamp(0.0, 1.0);
    let ch = |s: u32| (((c >> s) & 0xFF) as f32 * f + 0.5) as u32;
    (ch(16) << 16) | (ch(8) << 8) | ch(0)
}

/// The mean of some colours, channel by channel.
pub(crate) fn mean(cs: &[u32]) -> u32 {
    let n = cs.len().max(1) as u32;
    let ch = |s: u32| (cs.iter().map(|&c| (c >> s) & 0xFF).sum::<u32>() + n / 2) / n;
    (ch(16) << 16) | (ch(8) << 8) | ch(0)
}

/// `#rrggbb`.
pub(crate) fn hex(c: u32) -> String {
    format!("#{:06x}", c & 0xFF_FF_FF)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_is_distinct_for_hundreds() {
        let mut v: Vec<u32> = (0..400).map(categorical).collect();
        v.sort_unstable();
        v.dedup();
        assert_eq!(v.len(), 400);
        assert_eq!(shade(0xFF_80_00, 0.5), 0x80_40_00);
        assert_eq!(hex(0xAB), "#0000ab");
    }
}
