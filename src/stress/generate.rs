//! Random edit sessions: a garment of a random template, fit and resolution on the body,
//! then steps drawn from everything an editor does, with numbers from gentle to hostile:
//! dimensions changed within and far beyond their ranges, drags of random control points and
//! curves by random vectors from 0.1 mm to 1 m (log-uniform: every decade as likely), undos,
//! and the ease down to 0.

use crate::garment::template;
use crate::garment::{Collar, Sleeves, Style, TemplateKind};

use super::rng::Rng;

/// What a generated session may contain.
#[derive(Clone, Debug)]
pub struct GenerateOptions {
    /// Steps after the garment. Default 8.
    pub steps: usize,
    /// Probability that the scene builds M1 (slower; its own collision). Default 0.25.
    pub m1_chance: f64,
    /// Garment resolutions drawn from. Default 3..=6.
    pub resolutions: std::ops::RangeInclusive<usize>,
}

impl Default for GenerateOptions {
    fn default() -> Self {
        Self {
            steps: 8,
            m1_chance: 0.25,
            resolutions: 3..=6,
        }
    }
}

/// A drag's length: 0.1 mm to 1 m, log-uniform.
const DRAG_RANGE_M: (f64, f64) = (1e-4, 1.0);
/// A dimension's change: 0.1 mm to 0.5 m, log-uniform, either sign (beyond every range).
const CHANGE_RANGE_M: (f64, f64) = (1e-4, 0.5);

/// The text of session `rng` draws: `drape 1`, `body builtin` (the runner puts the real
/// body in its place), the garment, then `options.steps` steps.
pub fn session_text(rng: &mut Rng, options: &GenerateOptions) -> String {
    let kind = *rng.pick(&TemplateKind::ALL);
    // The jumpsuit and the shirt in any style: sleeves and a collar or neither.
    let style = if kind.takes_style() {
        Style {
            sleeves: *rng.pick(&Sleeves::ALL),
            collar: *rng.pick(&Collar::ALL),
        }
    } else {
        Style::default()
    };
    let t = template::styled(kind, style);
    let points = t.point_names();
    let curves = t.curve_names();
    let dimensions = t.dimension_names();
    let mut text = String::from("drape 1\nbody builtin\n");
    if rng.chance(options.m1_chance) {
        text.push_str("m1\n");
    }
    let (lo, hi) = (*options.resolutions.start(), *options.resolutions.end());
    let resolution = lo + rng.below(hi - lo + 1);
    let fit = if rng.chance(0.5) { "tight" } else { "loose" };
    text.push_str(&format!(
        "garment {}{} fit={fit} resolution={resolution}\n",
        kind.name(),
        if kind.takes_style() {
            format!(" sleeves={} collar={}", style.sleeves.name(), style.collar.name())
        } else {
            String::new()
        }
    ));
    // Steps that can be undone: every step after the garment is one (a refused step too).
    let mut undoable = 0usize;
    for _ in 0..options.steps {
        let roll = rng.unit();
        let line = if roll < 0.35 && !points.is_empty() {
            let v = vector(rng);
            format!("drag {} by={}", rng.pick(&points), v)
        } else if roll < 0.45 && !curves.is_empty() {
            let v = vector(rng);
            format!("drag {} by={}", rng.pick(&curves), v)
        } else if roll < 0.70 && !dimensions.is_empty() {
            let name = rng.pick(&dimensions).clone();
            let change = rng.log_range(CHANGE_RANGE_M.0, CHANGE_RANGE_M.1);
            let sign = if rng.chance(0.5) { "+" } else { "-" };
            format!("set {name} {sign}{}", number(change))
        } else if roll < 0.82 {
            // The ease itself: down to 0, tiny, or generous.
            let ease = match rng.below(4) {
                0 => 0.0,
                1 => rng.log_range(1e-7, 1e-3),
                _ => rng.range(0.0, 0.05),
            };
            format!("set ease {}", number(ease))
        } else if undoable > 0 {
            undoable -= 1;
            text.push_str("undo\n");
            continue;
        } else {
            let v = vector(rng);
            format!("drag {} by={}", rng.pick(&points), v)
        };
        undoable += 1;
        text.push_str(&line);
        text.push('\n');
    }
    text
}

/// A random drag vector, `x,y,z` in metres.
fn vector(rng: &mut Rng) -> String {
    let length = rng.log_range(DRAG_RANGE_M.0, DRAG_RANGE_M.1);
    let [x, y, z] = rng.direction();
    format!("{},{},{}", number(x * length), number(y * length), number(z * length))
}

/// A number as a session writes it: shortest round-trip form, so the text is exactly the
/// value drawn.
fn number(v: f64) -> String {
    let v = if v == 0.0 { 0.0 } else { v }; // no "-0"
    format!("{v}")
}
