//! `drape check-garment GARMENT --body BODY`: a garment made elsewhere, counted exactly
//! against the body, repaired by drape's collision layers, counted again; the repaired file
//! written with only the moved vertices changed; the exit code tells the outcome.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context as _;
use drape::body::{Body, BodyMesh, BodySource, Frame, LandmarkOptions, PartitionOptions};
use drape::collision::{BodyIndex, SliceOptions};
use drape::import::{CheckOptions, CheckReport, Checked, Counts, ImportedGarment, check};
use drape::mesh::{MeshDocument, MeshFormat};
use drape::session::{BodyStage, CollisionOutcome, CollisionPart, CollisionStage, Stage, StageInfo, StageSink};
use drape::viz::{LogOptions, RerunLogger, check_garment_blueprint, open_file_recording};

use crate::failure::{Classify, Result};
use crate::files::write_atomic;
use clap::Args;

pub(crate) const EXIT_CODES: &str = "Exit codes: 0 the garment was clear as read; 1 it was not, and the repair cleared it (--repair wrote the clear mesh); 4 the repair could not clear it (the regions left are printed); 2 bad input (an unreadable or malformed file, a non-manifold edge, a garment in other units or apart from the body, a body that cannot be analysed); 3 an internal or I/O failure.";

#[derive(Args, Debug)]
pub(crate) struct CheckGarmentArgs {
    /// The garment mesh: OBJ (triangles, quads or polygons), PLY (text or binary), glTF or
    /// GLB. Texture coordinates, normals, groups and materials are kept.
    pub(crate) garment: PathBuf,
    /// The body (OBJ, PLY, glTF or GLB; metres, y up, facing +z) [default: the built-in
    /// body].
    #[arg(long, value_name = "MESH")]
    pub(crate) body: Option<PathBuf>,
    /// The gap a moved vertex stands off the skin, m.
    #[arg(long, default_value_t = 0.002, value_parser = non_negative_metres)]
    pub(crate) ease: f64,
    /// The garment file's units.
    #[arg(long, default_value = "m", value_parser = ["m", "cm", "mm", "in"])]
    pub(crate) units: String,
    /// The axis that is up in the body's and the garment's files (x, y, z, -x, ...).
    #[arg(long, default_value = "y", value_parser = crate::args::parse_axis)]
    pub(crate) up: drape::body::Axis,
    /// The axis the body faces in the files.
    #[arg(long, default_value = "z", value_parser = crate::args::parse_axis)]
    pub(crate) front: drape::body::Axis,
    /// Write the repaired garment here, in the input's format (the input as read when it
    /// was already clear); a glTF garment may be written as .gltf or .glb.
    #[arg(long, value_name = "OUT")]
    pub(crate) repair: Option<PathBuf>,
    /// Print the report as JSON instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write a recording: the body with its partitions, the garment's problems before the
    /// repair, the responses, the garment after and its clearance.
    #[arg(long, value_name = "REC.rrd")]
    pub(crate) save: Option<PathBuf>,
}

fn non_negative_metres(text: &str) -> std::result::Result<f64, String> {
    let v: f64 = text.parse().map_err(|_| format!("'{text}' is not a number"))?;
    if v.is_finite() && (0.0..=0.1).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{text} m is not an ease between 0 and 0.1 m"))
    }
}

pub(crate) fn check_garment(args: &CheckGarmentArgs) -> Result<ExitCode> {
    let scale = match args.units.as_str() {
        "cm" => 0.01,
        "mm" => 0.001,
        "in" => 0.0254,
        _ => 1.0,
    };
    let source = args.body.clone().map_or(BodySource::Builtin, BodySource::File);
    let frame = Frame::new(args.up, args.front)
        .map_err(anyhow::Error::msg)
        .bad_input()?;
    let mesh = BodyMesh::load_bounded(&source, 1.0, crate::max_input_bytes())
        .context("cannot load the body")
        .bad_input()?
        .reoriented(frame);
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default())
        .context("cannot analyse the body")
        .bad_input()?;
    let slices = SliceOptions::default();
    let index = match crate::index_cache() {
        Some(cache) => cache.load_or_build(&body, &slices).0,
        None => BodyIndex::new(&body, &slices),
    };
    let mut doc = MeshDocument::read(&args.garment, scale, crate::max_input_bytes())
        .context("cannot read the garment")
        .bad_input()?;
    if !frame.is_identity() {
        doc.reorient(frame.to_drape());
    }
    if let Some(out) = &args.repair
        && let Some(format) = MeshFormat::of_path(out)
        && !doc.writes_as(format)
    {
        let back = match doc.format {
            MeshFormat::Gltf | MeshFormat::Glb => "glTF (name the file .gltf or .glb)".to_string(),
            other => format!("{} (name the file .{})", other.name(), other.extension()),
        };
        return Err(anyhow::anyhow!(
            "--repair {}: the garment is {}, written back as {back}",
            out.display(),
            doc.format.name(),
        ))
        .bad_input();
    }
    let garment = ImportedGarment::new(doc, &body.mesh.mesh, &index).bad_input()?;
    let options = CheckOptions {
        ease: args.ease,
        ..CheckOptions::default()
    };
    let checked = check(&garment, &index, &options);
    if let Some(out) = &args.repair {
        let format = MeshFormat::of_path(out).unwrap_or(garment.doc.format);
        let bytes = garment
            .doc
            .write_as(format, &checked.positions, &checked.moved)
            .internal()?;
        write_atomic(out, &bytes).internal()?;
    }
    if let Some(path) = &args.save {
        record(path, &body, &index, &garment, &checked).internal()?;
    }
    let report = &checked.report;
    if args.json {
        println!("{}", serde_json::to_string_pretty(report).internal()?);
    } else {
        print_report(report, &garment);
    }
    if let Some(out) = &args.repair {
        eprintln!("repaired garment: {}", out.display());
    }
    if let Some(path) = &args.save {
        eprintln!("recording: {} (view: rerun {})", path.display(), path.display());
    }
    Ok(ExitCode::from(report.status.exit_code()))
}

fn print_report(r: &CheckReport, garment: &ImportedGarment) {
    println!("{}: {}", r.file, garment.doc.summary());
    for line in r.notes.lines() {
        println!("  {line}");
    }
    println!(
        "{:<8} {:>8} {:>9} {:>8} {:>11} {:>15} {:>13}  regions",
        "", "inside", "crossing", "pierced", "deepest mm", "clearance mm", "face clr mm"
    );
    for (label, c) in [("before", &r.before), ("after", &r.after)] {
        println!(
            "{label:<8} {:>8} {:>9} {:>8} {:>11.2} {:>15.2} {:>13.2}  {}",
            c.inside_vertices,
            c.crossing_edges,
            c.pierced_faces,
            c.deepest_m * 1e3,
            c.vertex_clearance_m * 1e3,
            c.face_clearance_m * 1e3,
            regions(c)
        );
    }
    if let Some((v, p)) = r.before.deepest_at {
        println!(
            "deepest before: vertex {v} at ({:.4}, {:.4}, {:.4}) m, {:.2} mm inside",
            p[0],
            p[1],
            p[2],
            r.before.deepest_m * 1e3
        );
    }
    println!(
        "{}: {} vertices moved (farthest {:.2} mm, ease {:.1} mm); {:.1} ms to count, {:.1} ms to repair and certify",
        match r.status {
            drape::import::Status::Clear => "clear as read",
            drape::import::Status::Repaired => "repaired",
            drape::import::Status::NotClear => "NOT clear after the repair",
        },
        r.moved_vertices,
        r.max_move_m * 1e3,
        r.ease_m * 1e3,
        r.timings.before_ms,
        r.timings.repair_ms
    );
}

/// `A 3/1/0 C 2/0/0` (inside/crossing/pierced per region), or `-`.
fn regions(c: &Counts) -> String {
    if c.regions.is_empty() {
        return "-".into();
    }
    c.regions
        .iter()
        .map(|(k, r)| format!("{k} {}/{}/{}", r.inside, r.crossing, r.pierced))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The body with its rings and partitions, the garment's problems and the responses, the
/// garment after with its clearance: logged as a session logs M0's collision.
fn record(
    path: &std::path::Path,
    body: &Body,
    index: &BodyIndex,
    garment: &ImportedGarment,
    checked: &Checked,
) -> anyhow::Result<()> {
    crate::files::create_parent(path)?;
    let rec = open_file_recording(path, "check-garment", check_garment_blueprint())?;
    let mut logger = RerunLogger::new(rec.clone(), LogOptions::default())?;
    let outcome = CollisionOutcome {
        garment: garment.mesh.clone(),
        collision: checked.collision.clone(),
        verify: None,
        name: "garment".into(),
        source: None,
    };
    let stages = [
        ("body.load", Stage::Body(BodyStage::Mesh(&body.mesh))),
        ("body.rings", Stage::Body(BodyStage::Rings(&body.rings))),
        (
            "body.partitions",
            Stage::Body(BodyStage::Partitions(&body.mesh, &body.partitions)),
        ),
    ];
    for (k, (name, stage)) in stages.into_iter().enumerate() {
        let info = StageInfo {
            step: 0,
            op: "scene",
            stage: k as u64,
            name,
            layer: None,
        };
        logger.stage(&info, stage)?;
    }
    for (k, part) in CollisionPart::ALL.into_iter().enumerate() {
        let info = StageInfo {
            step: 1,
            op: "garment",
            stage: 3 + k as u64,
            name: part.stage_name(),
            layer: None,
        };
        logger.stage(
            &info,
            Stage::Collision(CollisionStage {
                outcome: &outcome,
                index,
                part,
            }),
        )?;
    }
    drop(logger);
    rec.flush_blocking()?;
    Ok(())
}
