//! Cameras: orthographic, with a rotation from the view name (or azimuth/elevation, z up),
//! fitted to the points it must show; or perspective from an eye point towards a target,
//! the target at the centre and the field of view just wide enough for the points in front.
use super::View;

/// A fitted camera. Orthographic: screen x = `cx + s * (R (p - c)).x`, screen y = `cy - s *
/// (R (p - c)).y`, depth = `s * (R (p - c)).z` (larger is nearer to the viewer). Perspective
/// (`c` = the eye, `d` = `-(R (p - c)).z` the distance in front of it): x and y divided by
/// `d`, depth = `s * d0 / d` (affine on the screen, larger is nearer, about one unit per pixel
/// at the target's distance `d0`); points closer than `d0 / 1000` project to NaN (dropped).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Camera {
    rot: [[f64; 3]; 3],
    centre: [f64; 3],
    scale: f64,
    screen_centre: [f64; 2],
    /// `Some(d0)`: perspective, the target at distance `d0` from the eye (`centre`).
    perspective: Option<f64>,
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n == 0.0 {
        v
    } else {
        [v[0] / n, v[1] / n, v[2] / n]
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The rows of the rotation (screen right, screen up, towards the viewer) for a view, z up.
pub(crate) fn rotation(view: View) -> [[f64; 3]; 3] {
    let (az, el) = match view {
        View::Top => return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        View::Front => (-90.0f64, 0.0f64),
        View::Side => (0.0, 0.0),
        View::Iso => (-45.0, 35.264_389_682_754_66),
        View::Angles { azimuth, elevation } => (azimuth, elevation),
    };
    let (az, el) = (az.to_radians(), el.clamp(-89.9, 89.9).to_radians());
    let e = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
    let x = normalize(cross([0.0, 0.0, 1.0], e));
    let y = cross(e, x);
    [x, y, e]
}

/// The rows of the rotation looking along `dir` (from the eye towards the target), z up (y up
/// when looking along z).
pub(crate) fn look_rotation(dir: [f64; 3]) -> [[f64; 3]; 3] {
    let e = normalize([-dir[0], -dir[1], -dir[2]]);
    let up = if e[0].abs() < 1e-9 && e[1].abs() < 1e-9 {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let x = normalize(cross(up, e));
    let y = cross(e, x);
    [x, y, e]
}

impl Camera {
    /// A perspective camera at `eye` looking at `target` (which lands at the centre of `rect`),
    /// its field of view just wide enough for the points of `pts` in front of the eye (at most
    /// about 127 degrees across the shorter side).
    pub(crate) fn look_at(
        eye: [f64; 3],
        target: [f64; 3],
        pts: impl Iterator<Item = [f64; 3]>,
        rect: [f64; 4],
    ) -> Camera {
        let dir = [0, 1, 2].map(|a| target[a] - eye[a]);
        let d0 = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        let mut cam = Camera {
            rot: look_rotation(dir),
            centre: eye,
            scale: 1.0,
            screen_centre: [0.5 * (rect[0] + rect[2]), 0.5 * (rect[1] + rect[3])],
            perspective: Some(d0),
        };
        let (hw, hh) = (0.5 * (rect[2] - rect[0]), 0.5 * (rect[3] - rect[1]));
        let near = 1e-3 * d0;
        let mut f = f64::INFINITY;
        for p in pts {
            let v = cam.view(p);
            let d = -v[2];
            if d > near {
                let (x, y) = ((v[0] / d).abs(), (v[1] / d).abs());
                if x > 0.0 {
                    f = f.min(hw / x);
                }
                if y > 0.0 {
                    f = f.min(hh / y);
                }
            }
        }
        let widest = 0.5 * hw.min(hh);
        cam.scale = if f.is_finite() {
            f.max(widest)
        } else {
            2.0 * hw.min(hh)
        };
        cam
    }

    /// A camera for `view` showing every point of `pts` inside the rectangle `rect` = (x0, y0,
    /// x1, y1) of the image.
    pub(crate) fn fit(
        view: View,
        pts: impl Iterator<Item = [f64; 3]> + Clone,
        rect: [f64; 4],
    ) -> Camera {
        let rot = rotation(view);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in pts.clone() {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        if !lo[0].is_finite() {
            lo = [0.0; 3];
            hi = [0.0; 3];
        }
        let centre = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
        let mut cam = Camera {
            rot,
            centre,
            scale: 1.0,
            screen_centre: [0.0, 0.0],
            perspective: None,
        };
        let (mut vlo, mut vhi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in pts {
            let v = cam.view(p);
            for a in 0..2 {
                vlo[a] = vlo[a].min(v[a]);
                vhi[a] = vhi[a].max(v[a]);
            }
        }
        let (w, h) = (rect[2] - rect[0], rect[3] - rect[1]);
        let (dx, dy) = ((vhi[0] - vlo[0]).max(0.0), (vhi[1] - vlo[1]).max(0.0));
        let s = match (dx > 0.0, dy > 0.0) {
            (true, true) => (w / dx).min(h / dy),
            (true, false) => w / dx,
            (false, true) => h / dy,
            (false, false) => 1.0,
        };
        cam.scale = if s.is_finite() && s > 0.0 { s } else { 1.0 };
        let (mx, my) = (0.5 * (vlo[0] + vhi[0]), 0.5 * (vlo[1] + vhi[1]));
        cam.screen_centre = [
            0.5 * (rect[0] + rect[2]) - cam.scale * mx,
            0.5 * (rect[1] + rect[3]) + cam.scale * my,
        ];
        cam
    }

    /// View coordinates of a point (rotated about the centre, not scaled).
    pub(crate) fn view(&self, p: [f64; 3]) -> [f64; 3] {
        let d = [
            p[0] - self.centre[0],
            p[1] - self.centre[1],
            p[2] - self.centre[2],
        ];
        self.rot.map(|r| r[0] * d[0] + r[1] * d[1] + r[2] * d[2])
    }

    /// Screen position (pixels, y down) and depth (pixels, larger is nearer).
    pub(crate) fn project(&self, p: [f64; 3]) -> [f64; 3] {
        let v = self.view(p);
        if let Some(d0) = self.perspective {
            let d = -v[2];
            if d <= 1e-3 * d0 {
                return [f64::NAN; 3];
            }
            return [
                self.screen_centre[0] + self.scale * v[0] / d,
                self.screen_centre[1] - self.scale * v[1] / d,
                self.scale * d0 / d,
            ];
        }
        [
            self.screen_centre[0] + self.scale * v[0],
            self.screen_centre[1] - self.scale * v[1],
            self.scale * v[2],
        ]
    }

    /// A direction (e.g. a normal) in view coordinates.
    pub(crate) fn rotate(&self, d: [f64; 3]) -> [f64; 3] {
        self.rot.map(|r| r[0] * d[0] + r[1] * d[1] + r[2] * d[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_are_rotations() {
        for v in [View::Iso, View::Front, View::Top, View::Side] {
            let r = rotation(v);
            for i in 0..3 {
                for j in 0..3 {
                    let d: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
                    assert!((d - f64::from(u8::from(i == j))).abs() < 1e-12, "{v:?}");
                }
            }
            // right-handed
            assert!((cross(r[0], r[1])[2] - r[2][2]).abs() < 1e-12);
        }
        // front: screen right is +x, screen up is +z
        let r = rotation(View::Front);
        assert!((r[0][0] - 1.0).abs() < 1e-12 && (r[1][2] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn fit_fills_the_rectangle() {
        let pts = [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0]];
        let c = Camera::fit(View::Top, pts.iter().copied(), [10.0, 10.0, 110.0, 210.0]);
        let a = c.project(pts[0]);
        let b = c.project(pts[1]);
        assert!((a[0] - 10.0).abs() < 1e-9 && (b[0] - 110.0).abs() < 1e-9);
        assert!(a[1] > b[1]); // y up on screen
    }

    #[test]
    fn perspective_puts_the_target_in_the_middle_and_shrinks_far_things() {
        let rect = [0.0, 0.0, 200.0, 100.0];
        let pts = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let c = Camera::look_at([0.0, -5.0, 0.5], [0.0, 0.0, 0.5], pts.iter().copied(), rect);
        let t = c.project([0.0, 0.0, 0.5]);
        assert!((t[0] - 100.0).abs() < 1e-9 && (t[1] - 50.0).abs() < 1e-9);
        // a unit step looks longer near the eye than far from it
        let near = c.project([1.0, -2.0, 0.5])[0] - c.project([0.0, -2.0, 0.5])[0];
        let far = c.project([1.0, 2.0, 0.5])[0] - c.project([0.0, 2.0, 0.5])[0];
        assert!(near > 1.5 * far, "{near} {far}");
        // nearer is larger depth; behind the eye is dropped
        assert!(c.project([0.0, -2.0, 0.5])[2] > c.project([0.0, 2.0, 0.5])[2]);
        assert!(c.project([0.0, -6.0, 0.5])[0].is_nan());
        // every point inside the rectangle
        for p in pts {
            let s = c.project(p);
            assert!(
                (-1e-9..=200.0 + 1e-9).contains(&s[0]) && (-1e-9..=100.0 + 1e-9).contains(&s[1])
            );
        }
        // looking straight down: still a rotation
        let r = look_rotation([0.0, 0.0, -1.0]);
        assert!((cross(r[0], r[1])[2] - r[2][2]).abs() < 1e-12 && (r[2][2] - 1.0).abs() < 1e-12);
    }
}
