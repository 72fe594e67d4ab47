//! A garment worn over others: its latest mesh coloured by its gap in front of the garment
//! right under it (`layer_gaps/<name>`, the fit map's bands: magenta behind it, red
//! within 2 mm, blue over 40 mm), and the garments under it muted (grey, in place of their
//! M0 at `garment/m0`, or `layers/<under>/garment/m0` for one worn over another).

use rerun::Clear;

use super::colors::{CLEARANCE_BANDS, clearance_band};
use super::draw::colored_mesh;
use super::logger::{RerunLogger, to_sink};
use crate::session::{Layered, SinkError, StageInfo};

/// The grey of a garment under another.
const MUTED: [u8; 3] = [175, 175, 180];

impl RerunLogger {
    /// Logs a garment worn over others (`info.layer` is its name).
    pub(super) fn log_layers(&mut self, info: &StageInfo, layered: &Layered) -> Result<(), SinkError> {
        let name = info.layer.as_deref().unwrap_or("outer");
        // The first time a garment worn over another is logged: the layout that shows it.
        if !self.layered.iter().any(|n| n == name) {
            self.layered.push(name.to_string());
            let activation = rerun::blueprint::BlueprintActivation {
                make_active: true,
                make_default: true,
            };
            super::blueprint::layered_blueprint(&self.layered)
                .send(&self.rec, activation)
                .map_err(to_sink)?;
        }
        let colors = layered
            .gaps
            .iter()
            .map(|&g| {
                if g.is_finite() {
                    CLEARANCE_BANDS[clearance_band(g)].1
                } else {
                    MUTED
                }
            })
            .collect();
        self.rec
            .log(format!("layer_gaps/{name}"), &colored_mesh(&layered.mesh, colors))
            .map_err(to_sink)?;
        for (k, (under, mesh)) in layered.under.iter().enumerate() {
            self.rec.set_layer((k > 0).then(|| under.clone()));
            let logged = self
                .rec
                .log("garment/m0/mesh", &Clear::recursive())
                .and_then(|()| self.rec.log("garment/m0/edges", &Clear::recursive()))
                .and_then(|()| {
                    self.rec.log(
                        "garment/m0/muted",
                        &colored_mesh(mesh, vec![MUTED; mesh.positions.len()]),
                    )
                });
            self.rec.set_layer(info.layer.clone());
            logged.map_err(to_sink)?;
        }
        Ok(())
    }
}
