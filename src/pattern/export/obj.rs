//! One piece as OBJ: its 3D positions (`v`, m), its 2D positions on the table (`vt`, m),
//! and its triangles (`f v/vt`, the same index for both).

use std::fmt::Write;

use crate::pattern::Piece;

/// The piece as OBJ text.
pub fn to_obj(piece: &Piece) -> String {
    let mut out = String::new();
    let d = &piece.distortion;
    let _ = writeln!(
        out,
        "# drape pattern piece {}: 3D positions (v, m) and flattened positions (vt, m); max strain {:.4}%, mean {:.4}%",
        piece.panel.name,
        100.0 * d.max_strain,
        100.0 * d.mean_strain
    );
    let _ = writeln!(out, "o {}", piece.panel.name);
    for p in &piece.panel.positions {
        let _ = writeln!(out, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    for t in &piece.uv {
        let _ = writeln!(out, "vt {:?} {:?}", t.x, t.y);
    }
    for t in &piece.panel.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        let _ = writeln!(out, "f {a}/{a} {b}/{b} {c}/{c}");
    }
    out
}
