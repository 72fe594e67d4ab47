//! The jumpsuit's seams, junction lines and patches, from its curves (\[frame\] section 4).

use glam::DVec3;

use crate::garment::anchors::{LEFT_LEG, RIGHT_LEG, TORSO};
use crate::garment::contour::clear_line;
use crate::garment::m0::CurveRef;
use crate::garment::model::{Counts, FeatureLine, Framework, FrameworkError};
use crate::garment::open_curve::OpenCurve;
use crate::garment::probe::BodyProbe;
use crate::garment::surface::{Surfacer, anchor, arc, contour, join, line, missing, open, reversed, through_at};
use crate::garment::template::{collar, sleeve};

use super::cut::Jumpsuit;

/// Segment counts of the bands, from the layout.
struct Bands {
    neck: usize,
    junction: usize,
    inner: usize,
    crotch: usize,
    strap: usize,
    torso: [usize; 3],
    leg: [usize; 2],
}

/// Shoulder seams (neckline side to strap top), crotch junctions (the inner contours'
/// span from the thigh), and with sleeves the armholes.
pub(super) fn lines(fw: &Framework, probe: &BodyProbe, cut: &Jumpsuit) -> Result<Vec<FeatureLine>, FrameworkError> {
    let Counts::Jumpsuit {
        seam: n_seam,
        inner: n_inner,
        strap: n_strap,
        ..
    } = fw.layout.counts
    else {
        return Err(missing("layout", "not a jumpsuit's"));
    };
    let gap = fw.layout.clearance;
    let mut lines = Vec::new();
    for (s, strap) in [("left", "left_strap"), ("right", "right_strap")] {
        lines.push(FeatureLine {
            name: format!("seam_{s}"),
            points: clear_line(anchor(fw, "neckline", s)?, open(fw, strap)?.apex, n_seam, probe, gap),
        });
    }
    for s in ["left", "right"].into_iter().filter(|_| cut.legs) {
        let c = contour(fw, &format!("inner_{s}"))?;
        let k = through_at(c, &format!("{s}_thigh"))?;
        lines.push(FeatureLine {
            name: format!("junction_{s}"),
            points: c.span(k, n_inner, Some((probe, gap))),
        });
    }
    if cut.style.sleeves != crate::garment::model::Sleeves::None {
        let Counts::Jumpsuit {
            armhole: upper,
            ref sleeve,
            ..
        } = fw.layout.counts
        else {
            return Err(missing("layout", "not a jumpsuit's"));
        };
        let k = fw.layout.k;
        lines.extend(sleeve::armhole_lower_lines(fw, k, probe, gap)?);
        // The ring halfway between the armpit and the shoulder point, across the panels
        // from armhole to armhole.
        let [l, r] = [0, 1].map(|side| sleeve::ArmholePoints::on(fw, side));
        let (l, r) = (l?, r?);
        lines.push(FeatureLine {
            name: "armpit_shoulder_front".into(),
            points: clear_line(r.front, l.front, 2 * k, probe, gap),
        });
        lines.push(FeatureLine {
            name: "armpit_shoulder_back".into(),
            points: clear_line(l.back, r.back, 2 * k, probe, gap),
        });
        let cap = sleeve.first().copied().unwrap_or(1);
        lines.extend(sleeve::cap_lines(fw, cap, probe, gap)?);
        let fitted = sleeve::armhole_lines(fw, &lines, upper, 48)?;
        lines.extend(fitted);
    }
    let _ = n_strap;
    Ok(lines)
}

/// Every patch of the jumpsuit: 24 around the torso, 8 at the crotch junction, 16 on the
/// legs, and the front and back panels up to the neckline.
pub(super) fn patches(s: &mut Surfacer<'_>, lines: &[FeatureLine], cut: &Jumpsuit) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let Counts::Jumpsuit {
        neck,
        junction,
        inner,
        crotch,
        strap,
        torso,
        leg,
        ref sleeve,
        armhole,
        collar,
        ..
    } = s.layout().counts
    else {
        return Err(missing("layout", "not a jumpsuit's"));
    };
    let sleeve_bands = sleeve.clone();
    let sleeved = cut.style.sleeves != crate::garment::model::Sleeves::None;
    let n = Bands {
        neck,
        junction,
        inner,
        crotch,
        strap,
        torso,
        leg,
    };
    let k = s.layout().k;
    torso_patches(s, &n, k)?;
    if cut.legs {
        let crotch = open(fw, "crotch")?;
        let crotch_front = reversed(crotch.half(true, n.crotch));
        let crotch_back = crotch.half(false, n.crotch);
        for side in ["left", "right"] {
            junction_patches(s, side, &n, k, (&crotch_front, &crotch_back))?;
            leg_patches(s, side, &n, k)?;
        }
    }
    if sleeved {
        sleeved_panels(s, lines, &n, k, armhole)?;
        underarm_triangles(s, lines, k)?;
        sleeve::sleeve_patches(s, lines, armhole, k, &sleeve_bands)?;
    } else {
        panels(s, lines, &n, k)?;
    }
    if cut.style.collar != crate::garment::model::Collar::None {
        collar::collar_patches(s, n.neck, collar)?;
    }
    Ok(())
}

/// The torso's patches: eight around (between the torso contours), three bands high (hip
/// to waist, waist to bust, bust to chest).
fn torso_patches(s: &mut Surfacer<'_>, n: &Bands, k: usize) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let torso_contours = [
        "centre_front",
        "front_left",
        "side_left",
        "back_left",
        "centre_back",
        "back_right",
        "side_right",
        "front_right",
    ];
    let torso_spans = [("hip", "waist"), ("waist", "bust"), ("bust", "chest")];
    for ((lo, hi), nv) in torso_spans.into_iter().zip(n.torso) {
        for i in 0..8 {
            let (a, b) = (TORSO[i], TORSO[(i + 1) % 8]);
            let bottom = arc(fw, lo, a, b, k)?;
            let top = arc(fw, hi, a, b, k)?;
            let left = s.span(torso_contours[i], lo, nv)?;
            let right = s.span(torso_contours[(i + 1) % 8], lo, nv)?;
            let curves = vec![
                CurveRef::whole(lo),
                CurveRef::whole(hi),
                s.span_ref(torso_contours[i], lo)?,
                s.span_ref(torso_contours[(i + 1) % 8], lo)?,
            ];
            s.patch(&format!("torso.{lo}_{hi}.{a}"), [&bottom, &top, &left, &right], curves)?;
        }
    }
    Ok(())
}

/// The junction of one leg (`side`): four patches between the thigh ring and the hip ring,
/// around the thigh in ring order, the inner seam running on into the crotch curve's halves
/// `(front, back)`.
fn junction_patches(
    s: &mut Surfacer<'_>,
    side: &str,
    n: &Bands,
    k: usize,
    (crotch_front, crotch_back): (&[DVec3], &[DVec3]),
) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let thigh = format!("{side}_thigh");
    let c = |name: &str| format!("{name}_{side}");
    let sp = |s: &Surfacer<'_>, name: &str| s.span(name, &thigh, n.junction);
    let inner_span = s.span(&c("inner"), &thigh, n.inner)?;
    let inner_front = join(&[inner_span.clone(), crotch_front.to_vec()]);
    let inner_back = join(&[inner_span, crotch_back.to_vec()]);
    // Around the thigh in ring order: five stops (thigh anchor, hip anchor, the boundary
    // between bands), the first and last both on the inner seam; a band between each
    // two. The right leg goes round the other way (the mirror of the left).
    let (stops, bands) = if side == "left" {
        (
            [
                ("inner", "front", inner_front),
                ("front", "front_left", sp(s, &c("front"))?),
                ("outer", "left", sp(s, &c("side"))?),
                ("back", "back_left", sp(s, &c("back"))?),
                ("inner", "back", inner_back),
            ],
            ["front_inner", "front_outer", "back_outer", "back_inner"],
        )
    } else {
        (
            [
                ("inner", "back", inner_back),
                ("back", "back_right", sp(s, &c("back"))?),
                ("outer", "right", sp(s, &c("side"))?),
                ("front", "front_right", sp(s, &c("front"))?),
                ("inner", "front", inner_front),
            ],
            ["back_inner", "back_outer", "front_outer", "front_inner"],
        )
    };
    let mut specs: Vec<(&str, [Vec<DVec3>; 4])> = Vec::with_capacity(4);
    for (band, w) in bands.into_iter().zip(stops.windows(2)) {
        let ((t0, h0, b0), (t1, h1, b1)) = (&w[0], &w[1]);
        specs.push((
            band,
            [
                arc(fw, &thigh, t0, t1, k)?,
                arc(fw, "hip", h0, h1, k)?,
                b0.clone(),
                b1.clone(),
            ],
        ));
    }
    let junction_curves = vec![
        CurveRef::whole(&thigh),
        CurveRef::whole("hip"),
        s.span_ref(&c("front"), &thigh)?,
        s.span_ref(&c("side"), &thigh)?,
        s.span_ref(&c("back"), &thigh)?,
        s.span_ref(&c("inner"), &thigh)?,
        CurveRef::whole("crotch"),
    ];
    for (name, [bottom, top, left, right]) in specs {
        s.patch(
            &format!("junction.{side}.{name}"),
            [&bottom, &top, &left, &right],
            junction_curves.clone(),
        )?;
    }
    Ok(())
}

/// One leg's patches (`side`): four around, between hem and knee and between knee and
/// thigh.
fn leg_patches(s: &mut Surfacer<'_>, side: &str, n: &Bands, k: usize) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let c = |name: &str| format!("{name}_{side}");
    let (order, cont) = if side == "left" {
        (LEFT_LEG, ["front", "side", "back", "inner"])
    } else {
        (RIGHT_LEG, ["front", "inner", "back", "side"])
    };
    for ((lo, hi), nv) in [("hem", "knee"), ("knee", "thigh")].into_iter().zip(n.leg) {
        let (lo_ring, hi_ring) = (format!("{side}_{lo}"), format!("{side}_{hi}"));
        for i in 0..4 {
            let (a, b) = (order[i], order[(i + 1) % 4]);
            let bottom = arc(fw, &lo_ring, a, b, k)?;
            let top = arc(fw, &hi_ring, a, b, k)?;
            let left = s.span(&c(cont[i]), &lo_ring, nv)?;
            let right = s.span(&c(cont[(i + 1) % 4]), &lo_ring, nv)?;
            let curves = vec![
                CurveRef::whole(&lo_ring),
                CurveRef::whole(&hi_ring),
                s.span_ref(&c(cont[i]), &lo_ring)?,
                s.span_ref(&c(cont[(i + 1) % 4]), &lo_ring)?,
            ];
            s.patch(
                &format!("leg.{side}.{lo}_{hi}.{a}"),
                [&bottom, &top, &left, &right],
                curves,
            )?;
        }
    }
    Ok(())
}

/// The panels' tops, front and back: the shoulder seams and the neckline between them.
fn panel_tops(fw: &Framework, lines: &[FeatureLine], n: &Bands) -> Result<[Vec<DVec3>; 2], FrameworkError> {
    let (seam_left, seam_right) = (line(lines, "seam_left")?, line(lines, "seam_right")?);
    let front_top = join(&[
        reversed(seam_right.to_vec()),
        arc(fw, "neckline", "right", "front", n.neck)?,
        arc(fw, "neckline", "front", "left", n.neck)?,
        seam_left.to_vec(),
    ]);
    let back_top = join(&[
        reversed(seam_left.to_vec()),
        arc(fw, "neckline", "left", "back", n.neck)?,
        arc(fw, "neckline", "back", "right", n.neck)?,
        seam_right.to_vec(),
    ]);
    Ok([front_top, back_top])
}

/// The panels' bottoms on the chest ring, front and back.
fn panel_bottoms(fw: &Framework, k: usize) -> Result<[Vec<DVec3>; 2], FrameworkError> {
    Ok([
        join(&[
            arc(fw, "chest", "front_right", "front", k)?,
            arc(fw, "chest", "front", "front_left", k)?,
        ]),
        join(&[
            arc(fw, "chest", "back_left", "back", k)?,
            arc(fw, "chest", "back", "back_right", k)?,
        ]),
    ])
}

/// With sleeves, the front and back panels in two each, below and above the ring halfway
/// between the armpit and the shoulder point: the lower ones between the chest ring and it,
/// the upper ones between it and the neckline, each held by the strap's part there (`k`
/// segments below `A`, `upper` above).
fn sleeved_panels(
    s: &mut Surfacer<'_>,
    lines: &[FeatureLine],
    n: &Bands,
    k: usize,
    upper: usize,
) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let [front_top, back_top] = panel_tops(fw, lines, n)?;
    let [front_bottom, back_bottom] = panel_bottoms(fw, k)?;
    let (mid_front, mid_back) = (
        line(lines, "armpit_shoulder_front")?.to_vec(),
        line(lines, "armpit_shoulder_back")?.to_vec(),
    );
    let part = |side: usize, front: bool, lower: bool| {
        sleeve::strap_part(fw, side, front, lower, if lower { k } else { upper })
    };
    let curves = panel_curves(&["armpit_shoulder_front", "armpit_shoulder_back"]);
    s.patch(
        "panel.front.lower",
        [&front_bottom, &mid_front, &part(1, true, true)?, &part(0, true, true)?],
        curves.clone(),
    )?;
    s.patch(
        "panel.front.upper",
        [&mid_front, &front_top, &part(1, true, false)?, &part(0, true, false)?],
        curves.clone(),
    )?;
    s.patch(
        "panel.back.lower",
        [&back_bottom, &mid_back, &part(0, false, true)?, &part(1, false, true)?],
        curves.clone(),
    )?;
    s.patch(
        "panel.back.upper",
        [&mid_back, &back_top, &part(0, false, false)?, &part(1, false, false)?],
        curves,
    )
}

/// With sleeves, the three-sided patches under each armhole, in front and behind: between
/// the chest ring's arc from its princess anchor to its side, the strap below `A` (or `A'`),
/// and the armhole's lower line from the side up to `A`; `k` segments a side. Corners in the
/// chest ring's order (counter-clockwise from above), so that they face out like their
/// neighbours.
fn underarm_triangles(s: &mut Surfacer<'_>, lines: &[FeatureLine], k: usize) -> Result<(), FrameworkError> {
    let fw = s.framework();
    for (side, sname) in ["left", "right"].into_iter().enumerate() {
        for front in [true, false] {
            let princess = format!("{}_{sname}", if front { "front" } else { "back" });
            // The chest arc in ring order, from `p` to `q`; one of them is the side.
            let (p, q) = match (sname, front) {
                ("left", true) | ("right", false) => (princess.clone(), sname.to_string()),
                _ => (sname.to_string(), princess.clone()),
            };
            let bottom = arc(fw, "chest", &p, &q, k)?;
            let strap = sleeve::strap_part(fw, side, front, true, k)?;
            let armhole = line(
                lines,
                &format!("{sname}_armhole_{}", if front { "front" } else { "back" }),
            )?
            .to_vec();
            // From `q` up to the armhole's point, and from there down to `p`.
            let (up, down) = if q == sname {
                (armhole, reversed(strap))
            } else {
                (strap, reversed(armhole))
            };
            let curves = ["chest", &format!("{sname}_strap")].map(CurveRef::whole).to_vec();
            s.triangle(
                &format!("underarm.{sname}.{}", if front { "front" } else { "back" }),
                [&bottom, &up, &down],
                curves,
            )?;
        }
    }
    Ok(())
}

/// The front and back panels between the chest ring, the straps and the neckline.
fn panels(s: &mut Surfacer<'_>, lines: &[FeatureLine], n: &Bands, k: usize) -> Result<(), FrameworkError> {
    let fw = s.framework();
    let (left_strap, right_strap) = (open(fw, "left_strap")?, open(fw, "right_strap")?);
    let strap = |c: &OpenCurve, front: bool| c.half(front, n.strap);
    let [front_top, back_top] = panel_tops(fw, lines, n)?;
    let [front_bottom, back_bottom] = panel_bottoms(fw, k)?;
    let curves = panel_curves(&[]);
    s.patch(
        "panel.front",
        [
            &front_bottom,
            &front_top,
            &strap(right_strap, true),
            &strap(left_strap, true),
        ],
        curves.clone(),
    )?;
    s.patch(
        "panel.back",
        [
            &back_bottom,
            &back_top,
            &reversed(strap(left_strap, false)),
            &reversed(strap(right_strap, false)),
        ],
        curves,
    )
}

/// The curves a panel's boundary comes from: the chest ring, the neckline, the straps and
/// the shoulder seams, and `more`.
fn panel_curves(more: &[&str]) -> Vec<CurveRef> {
    [
        "chest",
        "neckline",
        "left_strap",
        "right_strap",
        "seam_left",
        "seam_right",
    ]
    .iter()
    .chain(more)
    .map(|c| CurveRef::whole(c))
    .collect()
}
