//! An analytic dress form with neck and shoulders: the known surface the refinements are
//! measured against.
//!
//! `P(s, t) = C(s) + a(s) cos t X + b(s) sin t (1 + e(s) sin t) Z(s)` with `s` in `[0, 1]`
//! from the lower hip to the top of the neck and `t` the angle around the ring (`t = 0`
//! at the left side `+x`, `pi / 2` at the front `+z`). `C(s) = (0, y(s), c(s))` is the
//! ring centre, `a`, `b` the half width and half depth, `e` a front fullness (bust), and
//! `Z(s) = (0, -sin phi(s), cos phi(s))` tilts the neck rings forward-down as on a real
//! neck. All profile functions are sums of `tanh` steps and bells, so the surface is
//! smooth (C-infinity) and the heights `y(s)` increase, slowly across the shoulder slope
//! where the half width falls from the shoulder point to the neck.

use glam::DVec3;

use super::RingGrid;

/// Regions of the form, by profile parameter `s`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// `s < 0.25`.
    Hip,
    /// `0.25 <= s < 0.45`.
    Waist,
    /// `0.45 <= s < 0.65`.
    Bust,
    /// `0.65 <= s < 0.86`: up to and across the shoulder slope.
    Shoulder,
    /// `s >= 0.86`.
    Neck,
}

impl Region {
    /// Bottom to top.
    pub const ALL: [Self; 5] = [Self::Hip, Self::Waist, Self::Bust, Self::Shoulder, Self::Neck];
    /// The reporting order of the issue: neck first.
    pub const REPORT_ORDER: [Self; 5] = [Self::Neck, Self::Shoulder, Self::Bust, Self::Waist, Self::Hip];

    /// Name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Hip => "hip",
            Self::Waist => "waist",
            Self::Bust => "bust",
            Self::Shoulder => "shoulder",
            Self::Neck => "neck",
        }
    }

    /// The region of parameter `s`.
    pub fn of(s: f64) -> Self {
        match s {
            s if s < 0.25 => Self::Hip,
            s if s < 0.45 => Self::Waist,
            s if s < 0.65 => Self::Bust,
            s if s < 0.86 => Self::Shoulder,
            _ => Self::Neck,
        }
    }
}

/// The analytic dress form (all lengths in metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DressForm {
    /// Height of the lower edge (`s = 0`), m.
    pub base_y: f64,
}

impl Default for DressForm {
    fn default() -> Self {
        Self { base_y: 0.80 }
    }
}

/// Logistic step from 0 to 1 centred at `c` with width `w`.
fn step(s: f64, c: f64, w: f64) -> f64 {
    0.5 * (1.0 + ((s - c) / w).tanh())
}

/// Bell of height 1 centred at `c` with width `w`.
fn bell(s: f64, c: f64, w: f64) -> f64 {
    let u = (s - c) / w;
    (-u * u).exp()
}

impl DressForm {
    /// Ring centre height at `s` (0 at the lower edge, 1 at the top), m.
    pub fn y(&self, s: f64) -> f64 {
        // y' = 0.75 - 0.09 sech^2((s - 0.78) / 0.07) / 0.14: steepest body, flattest shoulder.
        self.base_y + 0.75 * s - 0.09 * step(s, 0.78, 0.07)
    }

    /// Half width (along x), m.
    pub fn half_width(&self, s: f64) -> f64 {
        0.160 + 0.012 * bell(s, 0.10, 0.10) - 0.030 * step(s, 0.32, 0.05)
            + 0.035 * step(s, 0.58, 0.07)
            + 0.012 * bell(s, 0.74, 0.04)
            - 0.135 * step(s, 0.80, 0.025)
    }

    /// Half depth (along z), m.
    pub fn half_depth(&self, s: f64) -> f64 {
        0.105 + 0.010 * bell(s, 0.10, 0.10) - 0.020 * step(s, 0.32, 0.05) + 0.022 * bell(s, 0.53, 0.07)
            - 0.030 * step(s, 0.78, 0.04)
    }

    /// Forward offset (z) of the ring centre, m.
    pub fn centre_z(&self, s: f64) -> f64 {
        0.010 * bell(s, 0.53, 0.07) - 0.018 * step(s, 0.84, 0.04)
    }

    /// Front fullness `e`, unitless: the front half's depth is scaled by `1 + e sin t`.
    pub fn fullness(&self, s: f64) -> f64 {
        0.18 * bell(s, 0.53, 0.06)
    }

    /// Forward-down tilt of the ring plane, radians.
    pub fn tilt(&self, s: f64) -> f64 {
        0.30 * step(s, 0.92, 0.03)
    }

    /// The surface point `P(s, t)`, m (world frame): with `d = b sin t (1 + e sin t)`,
    /// `P = (a cos t, y(s) - d sin phi, z_c(s) + d cos phi)`.
    pub fn point(&self, s: f64, t: f64) -> DVec3 {
        let (a, b, e, phi) = (self.half_width(s), self.half_depth(s), self.fullness(s), self.tilt(s));
        let (st, ct) = t.sin_cos();
        let depth = b * st * (1.0 + e * st);
        DVec3::new(
            a * ct,
            self.y(s) - depth * phi.sin(),
            self.centre_z(s) + depth * phi.cos(),
        )
    }

    /// Partial derivatives `(dP/ds, dP/dt)` by central differences (step 1e-6).
    pub fn tangents(&self, s: f64, t: f64) -> (DVec3, DVec3) {
        let h = 1e-6;
        (
            (self.point(s + h, t) - self.point(s - h, t)) / (2.0 * h),
            (self.point(s, t + h) - self.point(s, t - h)) / (2.0 * h),
        )
    }

    /// The measured grid: `layers` rings at equal steps of `s`, `points` at equal steps of
    /// `t`, starting at the front and running counter-clockwise seen from above.
    pub fn measure(&self, layers: usize, points: usize) -> RingGrid {
        let mut positions = Vec::with_capacity(layers * points);
        for i in 0..layers {
            let s = i as f64 / (layers - 1).max(1) as f64;
            for j in 0..points {
                positions.push(self.point(s, ring_angle(j, points)));
            }
        }
        RingGrid {
            layers,
            points,
            positions,
        }
    }
}

/// Angle of point `j` of `n` around a ring: from the front (`t = pi/2`), decreasing `t`
/// so the ring runs counter-clockwise seen from above (front, left, back, right).
pub fn ring_angle(j: usize, n: usize) -> f64 {
    std::f64::consts::FRAC_PI_2 - std::f64::consts::TAU * j as f64 / n as f64
}
