//! The default layout sent with every recording: the 3D scene, metrics plots and the log.

use rerun::blueprint::components::PanelState;
use rerun::blueprint::{
    Blueprint, BlueprintPanel, Horizontal, SelectionPanel, Spatial2DView, Spatial3DView, Tabs, TextDocumentView,
    TextLogView, TimePanel, TimeSeriesView, Vertical,
};

use super::recording::METRIC_UNITS;

/// The pattern pieces in 2D (edges coloured by strain, seams, notches, grain), beside the
/// garment coloured by piece and by strain.
fn patterns_tab() -> rerun::blueprint::ContainerLike {
    Horizontal::new([
        Spatial2DView::new("Patterns").with_origin("/patterns/pieces").into(),
        Spatial3DView::new("Panels")
            .with_origin("/")
            .with_contents(["+ /body/mesh", "+ /patterns/garment/panels"])
            .into(),
        Spatial3DView::new("Pattern strain")
            .with_origin("/")
            .with_contents(["+ /patterns/garment/strain"])
            .into(),
    ])
    .with_column_shares([2.0, 1.0, 1.0])
    .with_name("Patterns")
    .into()
}

/// Top left, tabs: the Garment (M0 on the plain body, with its cut lines' stored form,
/// the collision marks and the framework) and the Body (partition tint, landmarks, rings,
/// partition bounds, dress forms, sections; labels on hover, the partition legend a table
/// in its own tab), the Patterns (the pieces in 2D beside the garment by piece and by
/// strain), the sculpt and NURBS views; below them a view of M1 on the body (patches coloured by the rule that refined them, its cut
/// lines, its crossing edges before and after its collision), a close view of the collision
/// (hits, response arrows, what is left; it frames itself on them) and one of the constraint
/// network with the feature curves (solver iterations on the `iter` timeline); on the right
/// the metrics, one tab per unit (counts, metres, millimetres, ratios, milliseconds), and the
/// per-stage log with the clearance scale and the partition table as tabs; the time panel on the `stage` timeline; the blueprint and selection panels
/// collapsed.
pub fn default_blueprint() -> Blueprint {
    layered_blueprint(&[])
}

/// The contents of the views that show garments worn over others.
struct Contents {
    garment: Vec<String>,
    m1: Vec<String>,
    clearance: Vec<String>,
}

impl Contents {
    fn new(layered: &[String]) -> Self {
        let each = |rules: &[&str]| -> Vec<String> {
            layered
                .iter()
                .flat_map(|name| {
                    rules
                        .iter()
                        .map(move |r| format!("{}/layers/{name}/{}", &r[..2], &r[2..]))
                })
                .collect()
        };
        let garment: Vec<String> = [
            "+ /body/mesh",
            "+ /garment/**",
            "+ /collision/**",
            "+ /constraints/**",
            "+ /nurbs/parts/**",
            "+ /nurbs/contacts",
            "+ /layers/**",
            "- /garment/clearance/**",
            "- /garment/m1/**",
            "- /garment/sculpt/**",
            "- /garment/cut_lines/**",
            "- /collision/m1/**",
        ]
        .into_iter()
        .map(String::from)
        .chain(each(&[
            "- garment/clearance/**",
            "- garment/m1/**",
            "- garment/sculpt/**",
            "- garment/cut_lines/**",
            "- collision/m1/**",
        ]))
        .collect();
        let m1: Vec<String> = [
            "+ /body/mesh",
            "+ /garment/m1/**",
            "+ /garment/cut_lines/**",
            "+ /collision/m1/**",
        ]
        .into_iter()
        .map(String::from)
        .chain(each(&[
            "+ garment/m1/**",
            "+ garment/cut_lines/**",
            "+ collision/m1/**",
        ]))
        .collect();
        let clearance: Vec<String> = std::iter::once("+ /garment/clearance/**".to_string())
            .chain(each(&["+ garment/clearance/**"]))
            .collect();
        Self { garment, m1, clearance }
    }
}

/// [`default_blueprint`] for a session that wears the garments `layered` over others (their
/// entities under `layers/<name>/`): the Garment view shows their M0, collision and
/// framework (not their M1, sculpt, cut lines or clearance), the M1 view their M1 and cut
/// lines, the Clearance view their clearance maps. The logger sends it when the first
/// garment worn over another is logged.
pub fn layered_blueprint(layered: &[String]) -> Blueprint {
    let Contents { garment, m1, clearance } = Contents::new(layered);
    Blueprint::new(
        Horizontal::new([
            Vertical::new([
                Tabs::new([
                    // M0 on the plain body, with the collision marks and the framework.
                    Spatial3DView::new("Garment")
                        .with_origin("/")
                        .with_contents(garment)
                        .into(),
                    // Garments worn over others: each one's gap in front of the one under
                    // it (the fit map's colours), over the muted garment under it.
                    Spatial3DView::new("Layers")
                        .with_origin("/")
                        .with_contents([
                            "+ /body/mesh",
                            "+ /garment/m0/mesh/**",
                            "+ /garment/m0/muted",
                            "+ /layer_gaps/**",
                        ])
                        .into(),
                    // The body's own stages: partition tint, landmarks, rings, partition
                    // bounds, the dress forms and sections.
                    Spatial3DView::new("Body")
                        .with_origin("/")
                        .with_contents(["+ /body/**", "- /body/mesh", "+ /mannequin/**", "+ /section/**"])
                        .into(),
                    // The sculpted garment: the region tinted with its edges, the pick, the
                    // radius, the displacement field and the active faces per level.
                    Spatial3DView::new("Sculpt")
                        .with_origin("/")
                        .with_contents([
                            "+ /body/mesh",
                            "+ /garment/sculpt/**",
                            "+ /sculpt/**",
                            "- /sculpt/levels/**",
                        ])
                        .into(),
                    // The last sculpt's adaptive levels: the faces active at each.
                    Spatial3DView::new("Sculpt levels")
                        .with_origin("/")
                        .with_contents(["+ /sculpt/levels/**", "+ /sculpt/pick", "+ /sculpt/radius"])
                        .into(),
                    patterns_tab(),
                    // NURBS parts on the body, with their contacts.
                    Spatial3DView::new("NURBS")
                        .with_origin("/")
                        .with_contents(["+ /body/mesh", "+ /nurbs/parts/**", "+ /nurbs/contacts"])
                        .into(),
                ])
                .into(),
                Horizontal::new([
                    Tabs::new([
                        Spatial3DView::new("M1").with_origin("/").with_contents(m1).into(),
                        Spatial3DView::new("Clearance")
                            .with_origin("/")
                            .with_contents(clearance)
                            .into(),
                    ])
                    .into(),
                    Spatial3DView::new("Collision")
                        .with_origin("/")
                        .with_contents(["+ /collision/**"])
                        .into(),
                    Spatial3DView::new("Constraints")
                        .with_origin("/")
                        .with_contents([
                            "+ /constraints/**",
                            "+ /garment/curves/**",
                            "- /garment/curves/straightened",
                        ])
                        .into(),
                ])
                .into(),
            ])
            .with_row_shares([3.0, 2.0])
            .into(),
            figures_and_log(),
        ])
        .with_column_shares([3.0, 1.0]),
    )
    .with_panels_collapsed("stage")
}

/// `drape check-garment --save`'s layout: the garment after its repair on the body, with
/// what detection found (by partition) and the response arrows; beside it the close view
/// of the collision and the garment's clearance map; the body's partitions; the log with
/// the clearance scale and the partition table.
pub fn check_garment_blueprint() -> Blueprint {
    Blueprint::new(
        Horizontal::new([
            Vertical::new([
                Tabs::new([
                    Spatial3DView::new("Garment")
                        .with_origin("/")
                        .with_contents([
                            "+ /body/mesh",
                            "+ /garment/**",
                            "+ /collision/**",
                            "- /garment/clearance/**",
                            "- /collision/m1/**",
                        ])
                        .into(),
                    Spatial3DView::new("Body")
                        .with_origin("/")
                        .with_contents(["+ /body/**", "- /body/mesh"])
                        .into(),
                ])
                .into(),
                Horizontal::new([
                    Spatial3DView::new("Collision")
                        .with_origin("/")
                        .with_contents(["+ /collision/**", "- /collision/m1/**"])
                        .into(),
                    Spatial3DView::new("Clearance")
                        .with_origin("/")
                        .with_contents(["+ /garment/clearance/**"])
                        .into(),
                ])
                .into(),
            ])
            .with_row_shares([3.0, 2.0])
            .into(),
            Tabs::new([
                TextLogView::new("Log").with_origin("/log").into(),
                TextDocumentView::new("Clearance scale")
                    .with_origin("/legend/clearance")
                    .into(),
                TextDocumentView::new("Partitions")
                    .with_origin("/legend/partitions")
                    .into(),
            ])
            .into(),
        ])
        .with_column_shares([3.0, 1.0]),
    )
    .with_panels_collapsed("stage")
}

/// The right column: the guarantee's figures first (what the collision left, per step),
/// then every figure of the steps by unit; below, the log with the clearance scale and the
/// partition table.
fn figures_and_log() -> rerun::blueprint::ContainerLike {
    Vertical::new([
        Tabs::new(
            std::iter::once(
                TimeSeriesView::new("Collision")
                    .with_origin("/metrics/count/guarantee")
                    .into(),
            )
            .chain(METRIC_UNITS.iter().map(|(unit, title)| {
                TimeSeriesView::new(*title)
                    .with_origin(format!("/metrics/{unit}"))
                    .into()
            })),
        )
        .into(),
        Tabs::new([
            TextLogView::new("Log").with_origin("/log").into(),
            TextDocumentView::new("Clearance scale")
                .with_origin("/legend/clearance")
                .into(),
            TextDocumentView::new("Partitions")
                .with_origin("/legend/partitions")
                .into(),
        ])
        .into(),
    ])
    .with_row_shares([1.0, 1.0])
    .into()
}

/// The [nurbs] experiment's layout: the near pose (the whole scene) above the crossing pose
/// (framed on the hulls where the surfaces cross), hulls per level on the `level` timeline;
/// the figures in metres and counts, and the log.
pub fn nurbs_blueprint() -> Blueprint {
    Blueprint::new(
        Horizontal::new([
            Vertical::new([
                Spatial3DView::new(
                    "Near pose: the leaf hulls the level opens (butterfly orange, leaf green), nearest points (control red, true blue)",
                )
                .with_origin("/nurbs/near")
                .with_contents(["+ /nurbs/near/hulls/**", "+ /nurbs/near/closest/**"])
                    .into(),
                Horizontal::new([
                    Spatial3DView::new("Scene")
                        .with_origin("/nurbs/near")
                        .with_contents(["+ /nurbs/near/leaf/**", "+ /nurbs/near/butterfly/**"])
                        .into(),
                    Spatial3DView::new("Crossing pose: hulls where the surfaces cross")
                        .with_origin("/nurbs/crossing")
                        .with_contents(["+ /nurbs/crossing/hulls/**"])
                        .into(),
                ])
                .into(),
            ])
            .with_row_shares([3.0, 2.0])
            .into(),
            Vertical::new([
                TimeSeriesView::new("Distances (m)").with_origin("/metrics/m").into(),
                TimeSeriesView::new("Hull pairs tested")
                    .with_origin("/metrics/count")
                    .into(),
                TextLogView::new("Log").with_origin("/log").into(),
            ])
            .into(),
        ])
        .with_column_shares([3.0, 1.0]),
    )
    .with_panels_collapsed("level")
}

/// `drape sculpt-compare`'s layout: the results side by side (no subdivision, uniform
/// Loop, adaptive Loop, adaptive to uniform's longest edge; each labelled with its
/// figures); below, the regions' edges close up, the adaptive levels' active faces, and
/// the log.
pub fn sculpt_blueprint() -> Blueprint {
    Blueprint::new(
        Vertical::new([
            Spatial3DView::new(
                "The same drag: no subdivision, uniform Loop, adaptive Loop, adaptive to uniform's longest edge (region tinted, its edges drawn)",
            )
            .with_origin("/sculpt_compare")
            .with_contents(["+ /sculpt_compare/**", "- /sculpt_compare/adaptive/levels/**"])
            .into(),
            Horizontal::new([
                Spatial3DView::new("The regions close up: their edges, the pick and radius")
                    .with_origin("/sculpt_compare")
                    .with_contents([
                        "+ /sculpt_compare/none/edges",
                        "+ /sculpt_compare/uniform/edges",
                        "+ /sculpt_compare/adaptive/edges",
                        "+ /sculpt_compare/adaptive_matched/edges",
                        "+ /sculpt_compare/none/drag/**",
                    ])
                    .into(),
                Spatial3DView::new("Adaptive: active faces per level (red 1, orange 2, green 3, blue 4)")
                    .with_origin("/sculpt_compare")
                    .with_contents(["+ /sculpt_compare/adaptive/levels/**"])
                    .into(),
                TextLogView::new("Log").with_origin("/log").into(),
            ])
            .into(),
        ])
        .with_row_shares([3.0, 1.0]),
    )
    .with_panels_collapsed("stage")
}

/// The time, blueprint and selection panels collapsed, the time panel on `timeline`.
trait CollapsedPanels {
    fn with_panels_collapsed(self, timeline: &str) -> Self;
}

impl CollapsedPanels for Blueprint {
    fn with_panels_collapsed(self, timeline: &str) -> Self {
        self.with_time_panel(
            TimePanel::new()
                .with_timeline(timeline)
                .with_state(PanelState::Collapsed),
        )
        .with_blueprint_panel(BlueprintPanel::new().with_state(PanelState::Collapsed))
        .with_selection_panel(SelectionPanel::new().with_state(PanelState::Collapsed))
    }
}
