//! The constraint network CNet (\[frame\] section 3): the curves and a matrix whose entry
//! `g_ij` holds the constraints between curve `i` and curve `j` (several per entry,
//! directed or not; `g_ii` holds a curve's self constraints). Built automatically from a
//! solved framework, for either template.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use glam::{DVec2, DVec3};

use super::curves::{self, CurveKind, CurveNode, curve_nodes};
use super::kinds::{Constraint, Kind, SAMPLES_PER_SPAN, mirror, signed_gap};
use crate::garment::template::{self, CurveRoles};
use crate::garment::{BodyProbe, Framework};

/// Settings of the network built for a template.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NetworkOptions {
    /// How far a planar curve may grow past its built extent, as a fraction of the body's
    /// height (default 0.08: 12.7 cm on 1.59 m): the half side of its design square is its
    /// largest built radius plus this.
    pub region_margin: f64,
}

impl Default for NetworkOptions {
    fn default() -> Self {
        Self { region_margin: 0.08 }
    }
}

/// The network.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintNet {
    /// The curves, in network order.
    pub curves: Vec<CurveNode>,
    /// Every constraint.
    pub constraints: Vec<Constraint>,
    /// `g_ij` for `i <= j`: the indices of the constraints between curves `i` and `j`.
    pub matrix: BTreeMap<(usize, usize), Vec<usize>>,
    /// Each planar curve's least clearance from the body as built (control points and
    /// samples), m; infinite for contours. The collision never asks more of a curve.
    pub clearance: Vec<f64>,
    /// The body's height, m: the scale of length tolerances (a tolerance is a fraction of
    /// it for lengths, radians for angles).
    pub scale: f64,
}

impl ConstraintNet {
    /// The network of a framework's template: the template says which curves mirror each
    /// other, which rings are centred, where open curves end and what drives a tangent.
    pub fn for_framework(fw: &Framework, probe: &BodyProbe, options: &NetworkOptions) -> Self {
        let roles = template::styled(fw.template, fw.style).roles();
        let curves = curve_nodes(fw);
        let mut out: Vec<Constraint> = Vec::new();
        let mid_x = mid_plane(fw, &roles);
        let h = fw.layout.height;
        self_constraints(fw, &curves, (&roles, options), (mid_x, h), &mut out);
        pair_constraints(fw, &curves, &roles, mid_x, &mut out);
        meeting_constraints(fw, &curves, &roles, &mut out);
        let mut matrix: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
        for (k, c) in out.iter().enumerate() {
            matrix.entry((c.i.min(c.j), c.i.max(c.j))).or_default().push(k);
        }
        let clearance = clearances(fw, &curves, probe);
        Self {
            curves,
            constraints: out,
            matrix,
            clearance,
            scale: h,
        }
    }

    /// Whether residual `r` of constraint `k` exceeds `tolerance`: a fraction of the body's
    /// height for a residual in metres, radians for an angle.
    pub fn violated(&self, k: usize, r: f64, tolerance: f64) -> bool {
        let unit = if self.constraints[k].kind.unit() == "rad" {
            1.0
        } else {
            self.scale
        };
        r > tolerance * unit
    }

    /// A curve's index by name.
    pub fn curve(&self, name: &str) -> Option<usize> {
        self.curves.iter().position(|c| c.name == name)
    }

    /// The constraints touching curve `c`, in priority order (then by index).
    pub fn touching(&self, c: usize) -> Vec<usize> {
        let mut out: Vec<usize> = (0..self.constraints.len())
            .filter(|&k| self.constraints[k].i == c || self.constraints[k].j == c)
            .collect();
        out.sort_by_key(|&k| (self.constraints[k].kind.priority(), k));
        out
    }

    /// Every constraint's residual on `fw`, in its kind's unit (m, or rad for tangents).
    pub fn residuals(&self, fw: &Framework) -> Vec<f64> {
        self.constraints.iter().map(|c| c.residual(fw, &self.curves)).collect()
    }

    /// A readable listing: the curves, the matrix's occupancy, and every entry with its
    /// constraints and their residuals on `fw`.
    pub fn describe(&self, fw: &Framework, tolerance: f64) -> String {
        let mut s = String::new();
        let residuals = self.residuals(fw);
        let _ = writeln!(
            s,
            "constraint network: {} curves, {} constraints in {} matrix entries",
            self.curves.len(),
            self.constraints.len(),
            self.matrix.len()
        );
        let mut by_kind: BTreeMap<&str, usize> = BTreeMap::new();
        for c in &self.constraints {
            *by_kind.entry(c.kind.name()).or_default() += 1;
        }
        let kinds: Vec<String> = by_kind.iter().map(|(k, n)| format!("{k} {n}")).collect();
        let _ = writeln!(s, "by kind: {}", kinds.join(", "));
        let _ = writeln!(s, "\ncurves:");
        for (k, c) in self.curves.iter().enumerate() {
            let _ = writeln!(
                s,
                "  {k:>2} {:<14} {:<8} {:>2} control points",
                c.name,
                c.kind.name(),
                curves::points(fw, c).len()
            );
        }
        let n = self.curves.len();
        let _ = writeln!(
            s,
            "\nmatrix g_ij (number of constraints; '.' none; row i, column j, self constraints on the diagonal):"
        );
        let _ = writeln!(
            s,
            "     {}",
            (0..n).map(|j| format!("{}", j % 10)).collect::<Vec<_>>().join("")
        );
        for i in 0..n {
            let row: String = (0..n)
                .map(|j| {
                    self.matrix
                        .get(&(i.min(j), i.max(j)))
                        .map_or('.', |v| char::from_digit(v.len().min(9) as u32, 10).unwrap_or('+'))
                })
                .collect();
            let _ = writeln!(s, "  {i:>2} {row}");
        }
        let _ = writeln!(s, "\nentries:");
        let violated = (0..residuals.len())
            .filter(|&k| self.violated(k, residuals[k], tolerance))
            .count();
        for ((i, j), list) in &self.matrix {
            let _ = writeln!(s, "  g[{i},{j}] {} - {}", self.curves[*i].name, self.curves[*j].name);
            for &k in list {
                let c = &self.constraints[k];
                let detail = match &c.kind {
                    Kind::Coincident { a, b } => {
                        format!(" {}#{a} = {}#{b}", self.curves[c.i].name, self.curves[c.j].name)
                    }
                    Kind::Symmetry { pairs, .. } => format!(" {} point pairs", pairs.len()),
                    Kind::Tangent { front } => format!(
                        " {} end of {} -> top of {}",
                        if *front { "front" } else { "back" },
                        self.curves[c.i].name,
                        self.curves[c.j].name
                    ),
                    _ => String::new(),
                };
                let _ = writeln!(
                    s,
                    "      #{k:<3} {:<16} priority {} {:<10} residual {:.3e} {}{}{detail}",
                    c.kind.name(),
                    c.kind.priority(),
                    if c.directed { "directed" } else { "undirected" },
                    residuals[k],
                    c.kind.unit(),
                    if self.violated(k, residuals[k], tolerance) {
                        " VIOLATED"
                    } else {
                        ""
                    },
                );
            }
        }
        let worst = residuals.iter().copied().fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "\n{violated} of {} constraints violated (tolerance {tolerance:e} of the body's height, or rad); largest residual {worst:.3e}",
            self.constraints.len()
        );
        s
    }
}

/// The index of the curve named `name`.
fn id(curves: &[CurveNode], name: &str) -> Option<usize> {
    curves.iter().position(|c| c.name == name)
}

/// Each planar curve's own constraints: coplanar, no self-crossing, inside a square region
/// of its plane; a ring outside the body by its ease (or the gap the built ring has where
/// that is less) and, centred on the mirror plane `mid_x`, symmetric.
fn self_constraints(
    fw: &Framework,
    curves: &[CurveNode],
    (roles, options): (&CurveRoles, &NetworkOptions),
    (mid_x, h): (f64, f64),
    out: &mut Vec<Constraint>,
) {
    for (k, c) in curves.iter().enumerate() {
        let Some(plane) = curves::plane(fw, c) else {
            continue;
        };
        let pts = curves::points(fw, c);
        let flat: Vec<DVec2> = pts.iter().map(|p| plane.project(*p)).collect();
        let centre = flat.iter().sum::<DVec2>() / flat.len().max(1) as f64;
        let r = flat
            .iter()
            .map(|q| (*q - centre).abs().max_element())
            .fold(0.0, f64::max);
        let half = r + options.region_margin * h;
        let polygon = vec![
            centre + DVec2::new(-half, -half),
            centre + DVec2::new(half, -half),
            centre + DVec2::new(half, half),
            centre + DVec2::new(-half, half),
        ];
        let mut own = |kind: Kind| {
            out.push(Constraint {
                kind,
                i: k,
                j: k,
                directed: false,
            })
        };
        own(Kind::Coplanar);
        own(Kind::NoSelfCrossing);
        own(Kind::InsidePolygon { polygon });
        if c.kind == CurveKind::Ring {
            let ring = &fw.rings[c.index];
            let section = ring.stages.convex.clone();
            let sflat: Vec<DVec2> = section.iter().map(|p| plane.project(*p)).collect();
            let most = match ring.ease {
                crate::garment::Ease::Uniform(e) => e,
                crate::garment::Ease::PerDirection {
                    front,
                    left,
                    back,
                    right,
                } => front.max(left).max(back).max(right),
            };
            // The ease, or the gap the built ring has where it is less (the control
            // points between eased samples sit a sagitta inside the eased polyline).
            let need = flat.iter().map(|q| signed_gap(*q, &sflat).min(most)).collect();
            own(Kind::OutsideBody { section, need });
            if let Some(pairs) = centred_pairs(fw, c, roles) {
                let rest = pairs.iter().map(|&(a, b)| pts[b] - mirror(pts[a], mid_x)).collect();
                own(Kind::Symmetry { mid_x, pairs, rest });
            }
        }
    }
}

/// Left-right pairs: the leg rings by anchor name, the straps point by point.
fn pair_constraints(fw: &Framework, curves: &[CurveNode], roles: &CurveRoles, mid_x: f64, out: &mut Vec<Constraint>) {
    for (k, c) in curves.iter().enumerate() {
        let Some(partner) = roles.right_of(&c.name) else {
            continue;
        };
        let Some(m) = id(curves, partner) else {
            continue;
        };
        if c.kind == CurveKind::Contour {
            continue;
        }
        let (pa, pb) = (curves::points(fw, c), curves::points(fw, &curves[m]));
        let pairs: Vec<(usize, usize)> = match c.kind {
            CurveKind::Ring => fw.rings[c.index]
                .anchors
                .iter()
                .filter_map(|a| fw.rings[curves[m].index].anchor(a.name).map(|b| (a.control, b.control)))
                .collect(),
            // The ends lie on the chest ring, whose own symmetry pairs them.
            _ => (1..pa.len().min(pb.len()).saturating_sub(1)).map(|i| (i, i)).collect(),
        };
        let rest = pairs.iter().map(|&(a, b)| pb[b] - mirror(pa[a], mid_x)).collect();
        out.push(Constraint {
            kind: Kind::Symmetry { mid_x, pairs, rest },
            i: k,
            j: m,
            directed: false,
        });
    }
}

/// Where curves meet: a contour through a ring's anchor or an open curve's apex, an open
/// curve's ends on a ring's anchors, and the contours that run on from an open curve's ends
/// (tangent).
fn meeting_constraints(fw: &Framework, curves: &[CurveNode], roles: &CurveRoles, out: &mut Vec<Constraint>) {
    for (j, c) in curves.iter().enumerate() {
        if c.kind != CurveKind::Contour {
            continue;
        }
        for (b, through) in fw.contours[c.index].through.iter().enumerate() {
            let Some((curve, point)) = through.split_once('.') else {
                continue;
            };
            let Some(i) = id(curves, curve) else {
                continue;
            };
            let a = match curves[i].kind {
                CurveKind::Ring => fw.rings[curves[i].index].anchor(point).map(|x| x.control),
                CurveKind::Open => Some(curves::points(fw, &curves[i]).len() / 2),
                CurveKind::Contour => None,
            };
            if let Some(a) = a {
                out.push(Constraint {
                    kind: Kind::Coincident { a, b },
                    i,
                    j,
                    directed: false,
                });
            }
        }
    }
    for (i, c) in curves.iter().enumerate() {
        if c.kind != CurveKind::Open {
            continue;
        }
        let n = curves::points(fw, c).len();
        if let Some(joint) = roles.ends_of(&c.name)
            && let Some(r) = id(curves, joint.ring)
        {
            let ring_ref = &fw.rings[curves[r].index];
            for (name, end) in joint.anchors.into_iter().zip([0, n - 1]) {
                if let Some(a) = ring_ref.anchor(name) {
                    out.push(Constraint {
                        kind: Kind::Coincident { a: a.control, b: end },
                        i: r,
                        j: i,
                        directed: false,
                    });
                }
            }
        }
        // Contours that run on from the curve's ends (the princess lines into the
        // straps).
        for t in roles.tangents.iter().filter(|t| t.curve == c.name) {
            if let Some(j) = id(curves, t.contour) {
                out.push(Constraint {
                    kind: Kind::Tangent { front: t.front },
                    i,
                    j,
                    directed: true,
                });
            }
        }
    }
}

/// Each curve's clearance from the body: the least signed distance of its points and
/// samples (infinite for a contour, which the network does not hold off the body).
fn clearances(fw: &Framework, curves: &[CurveNode], probe: &BodyProbe) -> Vec<f64> {
    curves
        .iter()
        .map(|c| {
            if c.kind == CurveKind::Contour {
                return f64::INFINITY;
            }
            let samples = curves::samples(fw, c, SAMPLES_PER_SPAN);
            curves::points(fw, c)
                .iter()
                .chain(samples.iter().map(|(_, p)| p))
                .map(|p| probe.signed_distance(*p))
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

/// The body's mid-plane `x` as the framework sees it: the plane of the template's mirror
/// curve (the jumpsuit's crotch curve), or the mean of the rings' `front` anchors.
fn mid_plane(fw: &Framework, roles: &CurveRoles) -> f64 {
    if let Some(c) = roles
        .mirror_plane
        .and_then(|name| fw.open_curves.iter().find(|c| c.name == name))
    {
        return c.plane.offset * c.plane.normal.x.signum();
    }
    let xs: Vec<f64> = fw
        .rings
        .iter()
        .filter_map(|r| r.anchor("front").map(|a| a.point.x))
        .collect();
    xs.iter().sum::<f64>() / xs.len().max(1) as f64
}

/// The mirror pairs of a centred ring's control points (`front_left` with `front_right`,
/// `front` with itself, ...), as the template names them; `None` for a ring off the centre
/// (a leg).
fn centred_pairs(fw: &Framework, c: &CurveNode, roles: &CurveRoles) -> Option<Vec<(usize, usize)>> {
    let r = &fw.rings[c.index];
    let names = roles.centred_pairs(&c.name)?;
    Some(
        names
            .iter()
            .filter_map(|(a, b)| Some((r.anchor(a)?.control, r.anchor(b)?.control)))
            .collect(),
    )
}

/// A displacement mirrored about a plane `x = const`: `(-dx, dy, dz)`.
pub fn mirror_vector(d: DVec3) -> DVec3 {
    DVec3::new(-d.x, d.y, d.z)
}
