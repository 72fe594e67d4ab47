//! The context a template's solve works in ([`BuildCtx`]) and the lookups it shares.

use glam::{DVec2, DVec3};

use super::FrameworkOptions;
use crate::body::rings::{RingPick, pick_rings};
use crate::body::{Body, LandmarkKind, Side};
use crate::garment::anchors::AnchorSpec;
use crate::garment::ease::Ease;
use crate::garment::model::{Counts, DimensionValue, Dimensions, FrameworkError, Layout, NamedPlane};
use crate::garment::probe::BodyProbe;
use crate::garment::ring::{BuiltRing, GarmentRing, RingInput, build_or_keep};
use crate::geom::{Plane, polygon, section_mesh};

/// What a template's solve works with: the body, its probe, the dimensions the session set,
/// the settings, and the dimensions reached so far. The helpers cut the body's sections,
/// build rings and read dimensions with their allowed ranges.
pub struct BuildCtx<'a> {
    /// The body.
    pub body: &'a Body,
    /// Its nearest-point index (clearance of contour spans and seams).
    pub probe: &'a BodyProbe,
    /// Dimensions the session set.
    pub dims: &'a Dimensions,
    /// Settings of the solve.
    pub options: &'a FrameworkOptions,
    /// The body's height, m.
    pub height: f64,
    /// The garment's ease (the `ease` dimension), m.
    pub ease: f64,
    /// The body's mid-plane `x`, m.
    pub mid_x: f64,
    /// Dimensions reached so far.
    pub dimensions: Vec<DimensionValue>,
    /// The rings the build before made, each taken again where its inputs are the same.
    pub previous: &'a [BuiltRing],
    /// The rings built (or taken) so far, with their inputs.
    pub built: Vec<BuiltRing>,
    /// How many of those were taken from `previous`.
    pub rings_kept: usize,
}

impl BuildCtx<'_> {
    /// Dimension `name`: the session's value or `default`, checked against `range`
    /// (inclusive); `reason` says in the error why the range is what it is. Recorded among
    /// the dimensions reached.
    pub fn value(&mut self, name: &str, default: f64, range: (f64, f64), reason: &str) -> Result<f64, FrameworkError> {
        let target = self.dims.get(name);
        let value = target.unwrap_or(default);
        if !(value.is_finite() && value >= range.0 && value <= range.1) {
            return Err(FrameworkError::Dimension {
                name: name.to_string(),
                value,
                reason: format!("{reason} ({:.4}..{:.4} here)", range.0, range.1),
            });
        }
        self.dimensions.push(DimensionValue {
            name: name.to_string(),
            value,
            target,
        });
        Ok(value)
    }

    /// The ease of ring `ring` (the `<ring>_ease` dimension; the garment's ease by default),
    /// at most a tenth of the body's height, m.
    pub fn ring_ease(&mut self, ring: &str) -> Result<f64, FrameworkError> {
        let global = self.ease;
        let cap = 0.1 * self.height;
        self.value(
            &format!("{ring}_ease"),
            global,
            (0.0, cap),
            "ease must be between 0 and a tenth of the body's height",
        )
    }

    /// The torso's section loop at height `y` (ring `name`, for messages).
    pub fn torso_loop(&self, name: &str, y: f64) -> Result<Vec<DVec3>, FrameworkError> {
        let b = &self.body;
        pick_rings(&b.mesh, &b.landmarks, (name, None), y, RingPick::Torso)
            .map_err(|e| section_error(name, e.to_string()))
            .map(|mut r| r.remove(0).points)
    }

    /// The body's section loop in `plane` around `centre`: of the closed loops, the smallest
    /// whose inside (in the plane) holds `centre`, else the one whose centroid is nearest.
    /// `None` when the plane cuts no closed loop.
    pub fn loop_around(&self, plane: &Plane, centre: DVec3) -> Option<Vec<DVec3>> {
        let loops: Vec<Vec<DVec3>> = section_mesh(&self.body.mesh.mesh, &self.body.mesh.adjacency, plane)
            .into_iter()
            .filter(|l| l.closed && l.points.len() >= 3)
            .map(|l| l.points)
            .collect();
        let c = plane.project(centre);
        let flat = |l: &[DVec3]| -> Vec<DVec2> { l.iter().map(|p| plane.project(*p)).collect() };
        let area = |l: &[DVec3]| polygon::signed_area(&flat(l)).abs();
        let off = |l: &[DVec3]| (l.iter().sum::<DVec3>() / l.len() as f64).distance(centre);
        loops
            .iter()
            .filter(|l| polygon::contains(&flat(l), c))
            .min_by(|a, b| area(a).total_cmp(&area(b)))
            .or_else(|| loops.iter().min_by(|a, b| off(a).total_cmp(&off(b))))
            .cloned()
    }

    /// Both legs' section loops at height `y`, each with its side.
    pub fn leg_loops(&self, name: &str, y: f64) -> Result<Vec<(Side, Vec<DVec3>)>, FrameworkError> {
        let b = &self.body;
        pick_rings(&b.mesh, &b.landmarks, (name, None), y, RingPick::Legs)
            .map_err(|e| section_error(name, e.to_string()))
            .map(|rings| rings.into_iter().map(|r| (r.side, r.points)).collect())
    }

    /// Builds ring `name` through every sub-step, meeting its girth target (the
    /// `<name>_girth` dimension) when set; its girth is recorded among the dimensions.
    pub fn ring(
        &mut self,
        name: &str,
        plane: Plane,
        raw: Vec<Vec<DVec3>>,
        anchors: &[AnchorSpec],
        ease: Ease,
    ) -> Result<GarmentRing, FrameworkError> {
        self.ring_with(name, &[], plane, raw, anchors, ease)
    }

    /// [`Self::ring`], its girth target the `<name>_girth` dimension or else the first of
    /// `shared` set (a dimension both sleeves share: `cuff_girth`).
    pub fn ring_with(
        &mut self,
        name: &str,
        shared: &[&str],
        plane: Plane,
        raw: Vec<Vec<DVec3>>,
        anchors: &[AnchorSpec],
        ease: Ease,
    ) -> Result<GarmentRing, FrameworkError> {
        let key = format!("{name}_girth");
        let target = self
            .dims
            .get(&key)
            .or_else(|| shared.iter().find_map(|k| self.dims.get(k)));
        let input = RingInput {
            name,
            plane,
            raw,
            anchors,
            mid_x: self.mid_x,
            ease,
            target,
        };
        let (built, kept) = build_or_keep(input, &self.options.ring, self.previous)?;
        let ring = built.ring.clone();
        self.built.push(built);
        self.rings_kept += usize::from(kept);
        self.dimensions.push(DimensionValue {
            name: key,
            value: ring.girth,
            target,
        });
        Ok(ring)
    }

    /// A ring's ease, each side (left, right) at most 45% of the gap to the nearest other
    /// body loop on that side at the ring's height (the other leg, an arm), so that the
    /// garment ring never reaches a neighbouring limb.
    pub fn limited_ease(&self, y: f64, raw: &[Vec<DVec3>], ease: f64) -> Ease {
        let b = &self.body;
        let loops = b.mesh.section(&Plane::horizontal(y));
        let mine: Vec<DVec3> = raw.iter().flatten().copied().collect();
        let centre = mine.iter().sum::<DVec3>() / mine.len().max(1) as f64;
        let (mut left, mut right) = (ease, ease);
        for l in &loops {
            let gap = l
                .points
                .iter()
                .map(|p| {
                    mine.iter()
                        .map(|q| DVec3::new(p.x - q.x, 0.0, p.z - q.z).length())
                        .fold(f64::INFINITY, f64::min)
                })
                .fold(f64::INFINITY, f64::min);
            // Zero gap: one of the ring's own loops.
            if gap <= 1e-9 * self.height || l.points.is_empty() {
                continue;
            }
            let c = l.points.iter().sum::<DVec3>() / l.points.len() as f64;
            if c.x > centre.x {
                left = left.min(0.45 * gap);
            } else {
                right = right.min(0.45 * gap);
            }
        }
        if left == ease && right == ease {
            Ease::Uniform(ease)
        } else {
            Ease::PerDirection {
                front: ease,
                left,
                back: ease,
                right,
            }
        }
    }

    /// The garment mesh's nominal edge at the resolution, m.
    pub fn edge_length(&self) -> f64 {
        self.height * 0.09 / self.options.resolution.max(1) as f64
    }

    /// Segments for a band `dy` high (stretched by `stretch`), so that the band's edges are
    /// about as long as a ring's at the resolution: at least 2.
    pub fn segments(&self, dy: f64, stretch: f64) -> usize {
        let edge = self.edge_length();
        ((dy.abs() * stretch / edge).round() as usize).max(2)
    }

    /// The layout with these counts.
    pub fn layout(&self, counts: Counts) -> Layout {
        Layout {
            height: self.height,
            clearance: self.ease,
            weld: self.options.weld_threshold * self.height,
            k: self.options.resolution.max(2),
            counts,
        }
    }

    /// A plane to draw, centred at `centre`.
    pub fn plane_for(&self, name: &str, plane: Plane, centre: DVec3) -> NamedPlane {
        NamedPlane {
            name: name.to_string(),
            plane,
            centre,
            extent: 0.16 * self.height,
        }
    }
}

/// A framework error about curve `curve`.
pub fn section_error(curve: &str, what: String) -> FrameworkError {
    FrameworkError::Section {
        curve: curve.to_string(),
        what,
    }
}

/// Ring `name` among `rings`.
pub fn find<'r>(rings: &'r [GarmentRing], name: &str) -> Result<&'r GarmentRing, FrameworkError> {
    rings
        .iter()
        .find(|r| r.name == name)
        .ok_or_else(|| section_error(name, "ring missing from the framework".into()))
}

/// Anchor `anchor` of ring `ring` among `rings`, m.
pub fn point(rings: &[GarmentRing], ring: &str, anchor: &str) -> Result<DVec3, FrameworkError> {
    find(rings, ring)?
        .anchor(anchor)
        .map(|a| a.point)
        .ok_or_else(|| section_error(ring, format!("anchor {anchor} missing")))
}

/// Landmark `kind` on `side` of the body, m.
pub fn landmark(body: &Body, kind: LandmarkKind, side: Side) -> Result<DVec3, FrameworkError> {
    body.landmarks
        .get(kind, side)
        .map(|l| l.position())
        .ok_or_else(|| section_error(kind.name(), "landmark missing".into()))
}
