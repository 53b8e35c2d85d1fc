//! The software rasterizer: a colour buffer, a depth buffer (larger is nearer) and a face-id
//! buffer; triangles sampled at pixel centres, lines, dots, filled rectangles.

/// No face at this pixel.
pub(crate) const NO_FACE: u32 = u32::MAX;

/// Colour, depth and face-id buffers of one picture.
pub(crate) struct Canvas {
    pub w: usize,
    pub h: usize,
    /// 0xRRGGBB per pixel, row by row from the top.
    pub px: Vec<u32>,
    pub depth: Vec<f32>,
    pub face: Vec<u32>,
}

impl Canvas {
    pub(crate) fn new(w: usize, h: usize, background: u32) -> Canvas {
        Canvas {
            w,
            h,
            px: vec![background; w * h],
            depth: vec![f32::NEG_INFINITY; w * h],
            face: vec![NO_FACE; w * h],
        }
    }

    /// Fills the triangle `a b c` (screen x, y, depth) where it is nearer than what is there:
    /// every pixel whose centre is inside or on an edge.
    #[cfg(test)]
    pub(crate) fn triangle(&mut self, a: [f32; 3], b: [f32; 3], c: [f32; 3], colour: u32, id: u32) {
        self.triangle_colours(a, b, c, [colour; 3], id);
    }

    /// As [`Canvas::triangle`], the colour interpolated linearly (in screen space) between the
    /// colours of the corners `a`, `b`, `c` (Gouraud).
    pub(crate) fn triangle_colours(
        &mut self,
        a: [f32; 3],
        b: [f32; 3],
        c: [f32; 3],
        colours: [u32; 3],
        id: u32,
    ) {
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        let (b, c, area, colours) = if area < 0.0 {
            (c, b, -area, [colours[0], colours[2], colours[1]])
        } else {
            (b, c, area, colours)
        };
        let flat = colours[0] == colours[1] && colours[1] == colours[2];
        let ch = |k: u32| colours.map(|x| ((x >> k) & 0xFF) as f32);
        let (cr, cg, cb) = (ch(16), ch(8), ch(0));
        let minx = a[0].min(b[0]).min(c[0]);
        let maxx = a[0].max(b[0]).max(c[0]);
        let miny = a[1].min(b[1]).min(c[1]);
        let maxy = a[1].max(b[1]).max(c[1]);
        if maxx < 0.0 || maxy < 0.0 || minx >= self.w as f32 || miny >= self.h as f32 {
            return;
        }
        // pixel i covers [i, i+1): centres i + 0.5 inside the box
        let x0 = ((minx - 0.5).ceil().max(0.0)) as usize;
        let x1 = ((maxx - 0.5).floor().min(self.w as f32 - 1.0)) as i64;
        let y0 = ((miny - 0.5).ceil().max(0.0)) as usize;
        let y1 = ((maxy - 0.5).floor().min(self.h as f32 - 1.0)) as i64;
        if x1 < x0 as i64 || y1 < y0 as i64 {
            return;
        }
        let inv = 1.0 / area;
        // edge functions e(p) = A x + B y + C, non-negative inside
        let edge = |p: [f32; 3], q: [f32; 3]| {
            let ea = -(q[1] - p[1]);
            let eb = q[0] - p[0];
            let ec = -(ea * p[0] + eb * p[1]);
            (ea, eb, ec)
        };
        let (a0, b0, c0) = edge(b, c); // weight of a
        let (a1, b1, c1) = edge(c, a); // weight of b
        let (a2, b2, c2) = edge(a, b); // weight of c
        for y in y0..=(y1 as usize) {
            let py = y as f32 + 0.5;
            let row = y * self.w;
            let px0 = x0 as f32 + 0.5;
            let mut w0 = a0 * px0 + b0 * py + c0;
            let mut w1 = a1 * px0 + b1 * py + c1;
            let mut w2 = a2 * px0 + b2 * py + c2;
            for x in x0..=(x1 as usize) {
                if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                    let z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) * inv;
                    let i = row + x;
                    if z > self.depth[i] {
                        self.depth[i] = z;
                        self.px[i] = if flat {
                            colours[0]
                        } else {
                            let mix = |q: [f32; 3]| {
                                (((w0 * q[0] + w1 * q[1] + w2 * q[2]) * inv + 0.5) as u32).min(255)
                            };
                            (mix(cr) << 16) | (mix(cg) << 8) | mix(cb)
                        };
                        self.face[i] = id;
                    }
                }
                w0 += a0;
                w1 += a1;
                w2 += a2;
            }
        }
    }

    /// A line `thick` pixels wide from `a` to `b`, depth-tested with `bias` towards the viewer
    /// (`None`: drawn on top of everything).
    pub(crate) fn line(
        &mut self,
        a: [f32; 3],
        b: [f32; 3],
        colour: u32,
        thick: usize,
        bias: Option<f32>,
    ) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        if !(dx.is_finite() && dy.is_finite()) {
            return;
        }
        let n = dx.abs().max(dy.abs()).ceil().clamp(1.0, 1.0e5) as usize;
        let r = thick as i64 / 2;
        for s in 0..=n {
            let t = s as f32 / n as f32;
            let x = (a[0] + t * dx).floor() as i64;
            let y = (a[1] + t * dy).floor() as i64;
            let z = a[2] + t * (b[2] - a[2]);
            for yy in y - r..y - r + thick as i64 {
                for xx in x - r..x - r + thick as i64 {
                    self.plot(xx, yy, z, colour, bias);
                }
            }
        }
    }

    fn plot(&mut self, x: i64, y: i64, z: f32, colour: u32, bias: Option<f32>) {
        if x < 0 || y < 0 || x >= self.w as i64 || y >= self.h as i64 {
            return;
        }
        let i = y as usize * self.w + x as usize;
        match bias {
            Some(b) => {
                if z + b >= self.depth[i] {
                    self.px[i] = colour;
                }
            }
            None => self.px[i] = colour,
        }
    }

    /// A filled disc of radius `r` at `p`, with a one-pixel `outline` ring, depth-tested like
    /// [`Canvas::line`].
    pub(crate) fn dot(
        &mut self,
        p: [f32; 3],
        r: f32,
        colour: u32,
        outline: Option<u32>,
        bias: Option<f32>,
    ) {
        let (cx, cy) = (p[0], p[1]);
        if !(cx.is_finite() && cy.is_finite()) {
            return;
        }
        let ro = if outline.is_some() { r + 1.5 } else { r };
        let (x0, x1) = ((cx - ro).floor() as i64, (cx + ro).ceil() as i64);
        let (y0, y1) = ((cy - ro).floor() as i64, (cy + ro).ceil() as i64);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (ddx, ddy) = (x as f32 + 0.5 - cx, y as f32 + 0.5 - cy);
                let d = (ddx * ddx + ddy * ddy).sqrt();
                if d <= r {
                    self.plot(x, y, p[2], colour, bias);
                } else if d <= ro
                    && let Some(o) = outline
                {
                    self.plot(x, y, p[2], o, bias);
                }
            }
        }
    }

    /// Fills the rectangle `[x0, x1) x [y0, y1)` (clipped), on top of everything.
    pub(crate) fn rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, colour: u32) {
        for y in y0.max(0)..y1.min(self.h as i64) {
            for x in x0.max(0)..x1.min(self.w as i64) {
                self.px[y as usize * self.w + x as usize] = colour;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_of_two_triangles_has_no_gap_and_no_overlap_area() {
        let mut c = Canvas::new(20, 20, 0);
        let (a, b, cc, d) = (
            [2.0, 2.0, 0.0],
            [12.0, 2.0, 0.0],
            [12.0, 12.0, 0.0],
            [2.0, 12.0, 0.0],
        );
        c.triangle(a, b, cc, 1, 0);
        c.triangle(a, cc, d, 2, 1);
        assert_eq!(c.px.iter().filter(|&&p| p != 0).count(), 100);
    }

    #[test]
    fn corner_colours_are_interpolated() {
        let mut c = Canvas::new(101, 3, 0);
        let (l, r) = (0x00_00_00, 0xC8_64_00);
        // a thin band from x = 0 to x = 101, black on the left, (200, 100, 0) on the right
        c.triangle_colours(
            [0.0, 0.0, 0.0],
            [101.0, 0.0, 0.0],
            [101.0, 3.0, 0.0],
            [l, r, r],
            0,
        );
        c.triangle_colours(
            [0.0, 0.0, 0.0],
            [101.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
            [l, r, l],
            1,
        );
        let mid = c.px[101 + 50];
        assert_eq!(mid >> 16, 100, "{mid:06x}");
        assert_eq!((mid >> 8) & 0xFF, 50, "{mid:06x}");
        assert!(c.px[101] >> 16 <= 2 && c.px[101 + 100] >> 16 >= 198);
    }

    #[test]
    fn nearer_wins() {
        let mut c = Canvas::new(10, 10, 0);
        c.triangle([0.0, 0.0, 5.0], [10.0, 0.0, 5.0], [0.0, 10.0, 5.0], 1, 0);
        c.triangle([0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0], 2, 1);
        assert_eq!(c.px[0], 1);
    }
}
