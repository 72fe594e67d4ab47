//! The default layout sent with every recording: the 3D scene, metrics plots and the log.

use rerun::blueprint::{Blueprint, Horizontal, Spatial3DView, TextLogView, TimePanel, TimeSeriesView, Vertical};

/// 3D view of everything spatial but M1 on the left (M0 with its cut lines' stored form),
/// above a view of M1 on the body (patches coloured by the rule that refined them, its cut
/// lines, its crossing edges before and after its collision), a close view of the collision
/// (hits, response arrows, what is left; it frames itself on them) and one of the constraint
/// network with the feature curves (solver iterations on the `iter` timeline); metrics and
/// the per-stage log on the right; the time panel on the `stage` timeline.
pub fn default_blueprint() -> Blueprint {
    Blueprint::new(
        Horizontal::new([
            Vertical::new([
                Spatial3DView::new("Scene")
                    .with_origin("/")
                    .with_contents([
                        "+ /body/**",
                        "+ /mannequin/**",
                        "+ /section/**",
                        "+ /garment/**",
                        "+ /collision/**",
                        "+ /constraints/**",
                        "- /garment/m1/**",
                        "- /garment/cut_lines/**",
                        "- /collision/m1/**",
                    ])
                    .into(),
                Horizontal::new([
                    Spatial3DView::new("M1")
                        .with_origin("/")
                        .with_contents([
                            "+ /body/mesh",
                            "+ /garment/m1/**",
                            "+ /garment/cut_lines/**",
                            "+ /collision/m1/**",
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
            Vertical::new([
                TimeSeriesView::new("Metrics").with_origin("/metrics").into(),
                TextLogView::new("Log").with_origin("/log").into(),
            ])
            .with_row_shares([1.0, 1.0])
            .into(),
        ])
        .with_column_shares([3.0, 1.0]),
    )
    .with_time_panel(TimePanel::new().with_timeline("stage"))
}
