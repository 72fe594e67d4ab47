//! The pattern as DXF in the AAMA/ASTM D6673 layout, millimetres: one block per piece,
//! named by the piece, holding its cut line as a closed polyline on layer 1, its grain line
//! on layer 7, its notches as short lines on layer 4 and its name as text (`Piece Name:
//! NAME`) on layer 1; each block inserted where the layout puts the piece. Written with the
//! `dxf` crate, version R2000 (`$INSUNITS` millimetres).

use ::dxf::entities::{Entity, EntityType, Insert, Line, Polyline, Text, Vertex};
use ::dxf::enums::{AcadVersion, DrawingUnits, Units};
use ::dxf::{Block, Drawing, Point};
use glam::DVec2;

use crate::pattern::Pattern;

/// Length of a notch mark, mm.
const NOTCH_MM: f64 = 6.0;

/// The pattern as DXF bytes (ASCII).
pub fn to_dxf(pattern: &Pattern) -> Result<Vec<u8>, String> {
    let mut drawing = Drawing::new();
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = Units::Millimeters;
    drawing.header.drawing_units = DrawingUnits::Metric;
    for piece in &pattern.pieces {
        // Block coordinates from the piece's lower left corner, inserted there.
        let origin = piece.uv.iter().fold(DVec2::INFINITY, |lo, p| lo.min(*p));
        let mm = |p: DVec2| Point::new(1e3 * (p.x - origin.x), 1e3 * (p.y - origin.y), 0.0);
        let on = |layer: &str, specific: EntityType| {
            let mut e = Entity::new(specific);
            e.common.layer = layer.to_string();
            e
        };
        let mut cut = Polyline::default();
        cut.set_is_closed(true);
        for &v in &piece.panel.boundary {
            cut.add_vertex(&mut drawing, Vertex::new(mm(piece.uv[v as usize])));
        }
        let mut entities = vec![on("1", EntityType::Polyline(cut))];
        entities.push(on(
            "7",
            EntityType::Line(Line::new(mm(piece.grain[0]), mm(piece.grain[1]))),
        ));
        for &(p, inward) in &piece.notches {
            entities.push(on(
                "4",
                EntityType::Line(Line::new(mm(p), mm(p + inward * (NOTCH_MM * 1e-3)))),
            ));
        }
        let text = Text {
            location: mm(0.5 * (piece.grain[0] + piece.grain[1])),
            text_height: 10.0,
            value: format!("Piece Name: {}", piece.panel.name),
            ..Default::default()
        };
        entities.push(on("1", EntityType::Text(text)));
        // Handles for the block's entities (and their layers in the table): added to the
        // drawing, which numbers them, then taken back out into the block.
        let entities = entities
            .into_iter()
            .filter_map(|e| {
                drawing.add_entity(e);
                let last = drawing.entities().count().checked_sub(1)?;
                drawing.remove_entity(last)
            })
            .collect();
        let block = Block {
            name: block_name(&piece.panel.name),
            layer: "0".into(),
            base_point: Point::origin(),
            entities,
            ..Default::default()
        };
        drawing.add_block(block);
        let insert = Insert {
            name: block_name(&piece.panel.name),
            location: Point::new(1e3 * origin.x, 1e3 * origin.y, 0.0),
            ..Default::default()
        };
        drawing.add_entity(Entity::new(EntityType::Insert(insert)));
    }
    // The writer gives each ENDBLK its BLOCK's handle; handles must be unique, so each
    // ENDBLK gets one of a range reserved here (and `$HANDSEED` moves past it).
    let reserved = drawing.header.next_available_handle;
    let spare = 2 * (pattern.pieces.len() + 8);
    for _ in 0..spare {
        drawing.header.next_available_handle = drawing.header.next_available_handle.next_handle_value();
    }
    let mut bytes = Vec::new();
    drawing.save(&mut bytes).map_err(|e| e.to_string())?;
    let text = String::from_utf8(bytes).map_err(|e| e.to_string())?;
    Ok(unique_endblk_handles(&text, reserved, spare)?.into_bytes())
}

/// `text` with the handle after every `ENDBLK` replaced by the next of `spare` handles from
/// `first`.
fn unique_endblk_handles(text: &str, first: ::dxf::Handle, spare: usize) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    let mut next = first;
    let mut used = 0;
    let mut lines = text.split_inclusive('\n').peekable();
    while let Some(line) = lines.next() {
        out.push_str(line);
        if line.trim() != "ENDBLK" {
            continue;
        }
        // The group code 5 and its value follow.
        let (Some(code), Some(value)) = (lines.next(), lines.next()) else {
            break;
        };
        out.push_str(code);
        if code.trim() == "5" {
            if used == spare {
                return Err("more blocks than handles reserved".into());
            }
            let eol = if value.ends_with("\r\n") { "\r\n" } else { "\n" };
            out.push_str(&next.as_string());
            out.push_str(eol);
            next = next.next_handle_value();
            used += 1;
        } else {
            out.push_str(value);
        }
    }
    Ok(out)
}

/// A block name from a piece name (DXF names take no `<>/\":;?*|=` and no spaces).
pub fn block_name(name: &str) -> String {
    name.chars()
        .map(|c| if "<>/\\\":;?*|=` ".contains(c) { '_' } else { c })
        .collect()
}
