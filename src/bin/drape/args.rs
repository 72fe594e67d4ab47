//! The command line's arguments (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

/// Exit codes, for `--help` and docs/guide.md.
pub(crate) const EXIT_CODES: &str = "Exit codes: 0 success; 1 a step failed at run time (the recording keeps \
every stage before it, plus the error), or with --strict a step left the garment in the body or an edit \
was refused; 2 bad input (a malformed session, flag or body file, or a session that `check` rejects); \
3 an internal or I/O failure (a file that cannot be written, a viewer that cannot be reached); \
130 stopped by Ctrl-C or SIGTERM after the current step (the recording, metrics and exports hold every \
finished step; a second signal stops at once).";

/// Garment edit sessions against a body, every stage logged to Rerun.
///
/// With no command, runs the built-in demo session and writes recordings/demo.rrd
/// (view it with `rerun recordings/demo.rrd`).
#[derive(Parser, Debug)]
#[command(name = "drape", version, about, long_about, after_help = EXIT_CODES)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
    /// The largest session or body file read, MiB: larger files, and anything that is not a
    /// regular file (a folder, a device, a pipe), are refused before reading.
    #[arg(long, global = true, value_name = "MB", default_value_t = 256, value_parser = clap::value_parser!(u64).range(1..=1_048_576))]
    pub(crate) max_input_mb: u64,
    /// Worker threads for the parallel parts (vertex and edge checks, patches, the ground
    /// truth) [default: one per core]. Results are the same, bit for bit, for any number.
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=16))]
    pub(crate) threads: Option<u16>,
    /// Where body indexes are kept between runs (one file per body, about 10 MB), so that
    /// a body's next session reads its index instead of building it [default: the user
    /// cache folder, ~/.cache/drape/index on Linux].
    #[arg(long, global = true, value_name = "DIR")]
    pub(crate) index_cache: Option<PathBuf>,
    /// Build the body index every run: read and write no index cache.
    #[arg(long, global = true, conflicts_with = "index_cache")]
    pub(crate) no_index_cache: bool,
    /// How many edits `undo` can take back: each keeps the garment whole (about 24 MB an
    /// edit for a jumpsuit at resolution 24 with M1), so the oldest are dropped past it.
    #[arg(long, global = true, value_name = "N", default_value_t = drape::session::DEFAULT_UNDO_LIMIT as u32, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub(crate) undo_limit: u32,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Run a session (default: the built-in demo) and log every stage to Rerun.
    #[command(after_help = EXIT_CODES)]
    Run(RunArgs),
    /// Parse and validate a session without running it.
    #[command(after_help = EXIT_CODES)]
    Check {
        /// The session file.
        session: PathBuf,
    },
    /// Print the constraint network of every garment the session builds: its curves, the
    /// matrix g_ij, and every constraint with its priority, direction and residual; then
    /// each drag's outcome.
    #[command(after_help = EXIT_CODES)]
    Constraints {
        /// The session file; without it, the built-in demo.
        session: Option<PathBuf>,
    },
    /// Edit interactively: type steps (or pipe them) one per line, each applied and logged
    /// at once; `help`, `show`, `save NAME`, `quit`.
    #[command(after_help = EXIT_CODES)]
    Edit(EditArgs),
    /// Run a recorded session (DIR/session.drape) again and compare the new logged data with
    /// the stored recording (DIR/recording.rrd), value by value, or with the digest in
    /// DIR/manifest.json; exit 1 with the first difference (step, stage, entity, component,
    /// row, index).
    #[command(after_help = EXIT_CODES)]
    Replay(ReplayArgs),
    /// Refine the analytic dress form both ways (polar and chord-length cubic splines)
    /// and print each method's deviation from the true surface per region.
    Mannequin(MannequinArgs),
    /// The [nurbs] L/T experiment: a butterfly (81 control points) held near a corn leaf
    /// (175), collided at subdivision levels 3..8 with the paper's control-point distance,
    /// the true surface distance beside it; a crossing pose that must be detected at every
    /// level; and the level and threshold recommended for --accuracy.
    #[command(name = "nurbs-experiment", after_help = EXIT_CODES)]
    NurbsExperiment(NurbsExperimentArgs),
    /// The [sculpt] comparison: one drag on the garment's collided M0 (or any OBJ mesh)
    /// with no subdivision, uniform Loop subdivision to the same longest edge, and adaptive
    /// Loop subdivision; prints faces, longest edge, smallest angle, smoothness and time
    /// for each, and logs the three side by side.
    #[command(name = "sculpt-compare", after_help = EXIT_CODES)]
    SculptCompare(SculptCompareArgs),
    /// Random edit sessions on every body (gentle to hostile numbers: dimensions beyond
    /// their ranges, drags from 0.1 mm to 1 m, undos, the ease down to 0), each judged:
    /// steps accepted, refused (by reason) and failed, panics, NaN or infinite outputs,
    /// garments left in the body, solver residuals, time per step. Exit 1 if any panic,
    /// non-finite value or garment left in the body; each such session is shrunk to its
    /// fewest steps and written (--out) so that `drape run FILE` replays it.
    #[command(after_help = STRESS_HELP, args_conflicts_with_subcommands = true)]
    Stress(StressArgs),
    /// Flatten panel meshes (OBJ; for example the `_panel_` files of --patterns) with
    /// drape's LSCM and ARAP, free boundary, and print per panel the time, the edge strain
    /// (max and mean) and the flipped triangles: the same question libigl's LSCM and ARAP
    /// answer (scripts/pattern_peers.py puts them side by side).
    #[command(after_help = EXIT_CODES)]
    Flatten(FlattenArgs),
    /// Check a garment mesh made elsewhere (OBJ, PLY, glTF, GLB) against a body and repair it: prints the
    /// exact counts before and after (garment vertices inside, garment edges crossing the
    /// body, body edges through garment faces, the deepest point, the least clearance, the
    /// body regions A-G they are in), repaired by drape's collision layers; `--repair`
    /// writes the file back with only the moved vertices (and the normals they use)
    /// changed, every other line as it was.
    #[command(after_help = crate::check_garment::EXIT_CODES)]
    CheckGarment(crate::check_garment::CheckGarmentArgs),
    /// Measure the whole edit step a user waits for: the demo session at resolutions 3, 6,
    /// 12 and 24, per stage, on one core and on every core; cold detection beside FCPW,
    /// Open3D and libigl asked the same question on the same points in the same run; and
    /// the growth against the garment's vertices and the body's triangles (the body split 4x
    /// and 16x). A few minutes; prints Markdown (--write puts it into a page).
    #[command(after_help = EXIT_CODES)]
    Bench(crate::bench::BenchArgs),
}

pub(crate) fn parse_axis(text: &str) -> Result<drape::body::Axis, String> {
    drape::body::Axis::parse(text).ok_or_else(|| format!("'{text}' is not an axis: give x, y, z, -x, -y or -z"))
}

#[derive(Args, Debug)]
pub(crate) struct FlattenArgs {
    /// Panel meshes (OBJ, PLY, glTF or GLB; metres).
    #[arg(required = true)]
    pub(crate) panels: Vec<PathBuf>,
    /// The method: LSCM alone, or ARAP started from it.
    #[arg(long, default_value = "arap", value_parser = ["arap", "lscm"])]
    pub(crate) method: String,
    /// Runs per panel; the time printed is the fastest.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=1000))]
    pub(crate) runs: u64,
    /// Print JSON lines instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
}

const STRESS_HELP: &str = "Sweeps over many machines: --shard I/N runs the sessions whose number is I modulo N \
(0 <= I < N), the same sessions on every machine; `drape stress merge a.json b.json ...` joins the --report files \
of the shards into the report of the whole sweep. See the array-job recipe (Slurm, Kubernetes) in docs/testing.md.";

#[derive(Args, Debug)]
pub(crate) struct StressArgs {
    #[command(subcommand)]
    pub(crate) command: Option<StressCommand>,
    /// Every .obj in this folder, in name order [default: the built-in body].
    #[arg(long, value_name = "DIR")]
    pub(crate) bodies: Option<PathBuf>,
    /// Sessions per body.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pub(crate) sessions: u64,
    /// Steps per session after the garment.
    #[arg(long, default_value_t = 8, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=1000))]
    pub(crate) steps: usize,
    /// The seed: session K under seed S is the same session everywhere, always.
    #[arg(long, default_value_t = 1)]
    pub(crate) seed: u64,
    /// Run only shard I of N (I counted from 0).
    #[arg(long, value_name = "I/N", default_value = "0/1", value_parser = parse_shard)]
    pub(crate) shard: (u64, u64),
    /// Print the report as JSON (records and totals) instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    /// Also write the JSON report here (what `stress merge` reads).
    #[arg(long, value_name = "PATH")]
    pub(crate) report: Option<PathBuf>,
    /// Where sessions that found a bug are written.
    #[arg(long, value_name = "DIR", default_value = "tests/fixtures/stress")]
    pub(crate) out: PathBuf,
    /// Write failing sessions as generated, without shrinking them.
    #[arg(long)]
    pub(crate) no_shrink: bool,
    /// Print the text of session K (under --seed and --steps) and run nothing.
    #[arg(long, value_name = "K")]
    pub(crate) show: Option<u64>,
    /// Check every collision as `drape run --verify` does: detection and the quality check
    /// against the brute-force truth, the step's quality check (partial) against a full
    /// one, and the time of both (seconds a step). A quality check that disagrees is a bug.
    #[arg(long)]
    pub(crate) verify: bool,
}

#[derive(Subcommand, Debug)]
pub(crate) enum StressCommand {
    /// Join the JSON reports of the shards of one sweep (same seed, sessions, steps).
    Merge {
        /// The reports (`drape stress --shard I/N --report FILE`).
        #[arg(required = true)]
        reports: Vec<PathBuf>,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

/// `I/N` with `I < N`.
fn parse_shard(s: &str) -> Result<(u64, u64), String> {
    let (i, n) = s
        .split_once('/')
        .ok_or_else(|| format!("'{s}': expected I/N, e.g. 0/4"))?;
    let i: u64 = i.trim().parse().map_err(|_| format!("'{s}': I is not a number"))?;
    let n: u64 = n.trim().parse().map_err(|_| format!("'{s}': N is not a number"))?;
    if n == 0 || i >= n {
        return Err(format!("'{s}': need 0 <= I < N"));
    }
    Ok((i, n))
}

#[derive(Args, Debug)]
pub(crate) struct EditArgs {
    /// A session to start from (its scene and steps); without it, the built-in body.
    pub(crate) session: Option<PathBuf>,
    /// Write the live recording here (also with a viewer or a server: it keeps everything
    /// if the viewer goes away).
    #[arg(long, value_name = "PATH", default_value = "recordings/edit.rrd")]
    pub(crate) save: PathBuf,
    /// A viewer instead of the file.
    #[command(flatten)]
    pub(crate) viewer: ViewerArgs,
}

/// Where a live recording goes besides its file.
#[derive(Args, Debug)]
pub(crate) struct ViewerArgs {
    /// Stream to a running viewer, e.g. rerun+http://host:9876/proxy (the file is written
    /// too, and keeps everything if the viewer goes away).
    #[arg(long, value_name = "URL", conflicts_with_all = ["serve", "serve_web"])]
    pub(crate) connect: Option<String>,
    /// Serve the recording over gRPC for viewers to join (now or later) until Ctrl-C; the
    /// file is closed when serving stops.
    #[arg(long)]
    pub(crate) serve: bool,
    /// As --serve, and serve Rerun's web viewer over HTTP too: a browser is all a remote
    /// person needs (open the printed URL).
    #[arg(long, conflicts_with = "serve")]
    pub(crate) serve_web: bool,
    /// gRPC port for --serve and --serve-web.
    #[arg(long, default_value_t = 9876)]
    pub(crate) port: u16,
    /// HTTP port of the web viewer for --serve-web.
    #[arg(long, default_value_t = 9090, requires = "serve_web")]
    pub(crate) web_port: u16,
    /// The address --serve and --serve-web listen on. The default, 127.0.0.1, serves this
    /// machine only: from another machine, tunnel first (ssh -L 9876:localhost:9876 -L
    /// 9090:localhost:9090 HOST). 0.0.0.0 (or one interface's address) opens the servers to a
    /// network: Rerun's servers have no authentication, so anyone who can reach the ports
    /// can open the recording (a body scan is personal data).
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub(crate) bind: std::net::IpAddr,
}

impl Default for ViewerArgs {
    fn default() -> Self {
        Self {
            connect: None,
            serve: false,
            serve_web: false,
            port: 9876,
            web_port: 9090,
            bind: LOCAL,
        }
    }
}

/// Where servers listen unless told: this machine only.
pub(crate) const LOCAL: std::net::IpAddr = std::net::IpAddr::V4(std::net::Ipv4Addr::LOCALHOST);

#[derive(Args, Debug)]
pub(crate) struct ReplayArgs {
    /// The recording's folder (recordings/NAME).
    pub(crate) dir: PathBuf,
    /// Floats equal when they differ by at most this much [default: exact].
    #[arg(long, default_value_t = 0.0)]
    pub(crate) tolerance: f64,
    /// Record the session into the folder (recording.rrd and manifest.json) instead.
    #[arg(long, conflicts_with = "serve")]
    pub(crate) write: bool,
    /// Serve the recorded session to viewers (now or later) until Ctrl-C, instead of
    /// comparing: the session is run again into a gRPC server (the same data, which a
    /// plain replay proves).
    #[arg(long)]
    pub(crate) serve: bool,
    /// As --serve, and serve Rerun's web viewer over HTTP too (open the printed URL).
    #[arg(long, conflicts_with_all = ["serve", "write"])]
    pub(crate) serve_web: bool,
    /// gRPC port for --serve and --serve-web.
    #[arg(long, default_value_t = 9876)]
    pub(crate) port: u16,
    /// HTTP port of the web viewer for --serve-web.
    #[arg(long, default_value_t = 9090, requires = "serve_web")]
    pub(crate) web_port: u16,
    /// The address --serve and --serve-web listen on. The default, 127.0.0.1, serves this
    /// machine only: from another machine, tunnel first (ssh -L 9876:localhost:9876 -L
    /// 9090:localhost:9090 HOST). 0.0.0.0 (or one interface's address) opens the servers to a
    /// network: Rerun's servers have no authentication, so anyone who can reach the ports
    /// can open the recording (a body scan is personal data).
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub(crate) bind: std::net::IpAddr,
}

#[derive(Args, Debug, Default)]
pub(crate) struct RunArgs {
    /// Session file; without it, the built-in demo (assets/sessions/demo.drape).
    pub(crate) session: Option<PathBuf>,
    /// Use this body (OBJ, PLY, glTF or GLB; metres, y up, facing +z) instead of the
    /// session's.
    #[arg(long, value_name = "MESH")]
    pub(crate) body: Option<PathBuf>,
    /// The axis that is up in the body's file (x, y, z, -x, ...) [default: y].
    #[arg(long, value_parser = parse_axis)]
    pub(crate) up: Option<drape::body::Axis>,
    /// The axis the body faces in its file [default: z].
    #[arg(long, value_parser = parse_axis)]
    pub(crate) front: Option<drape::body::Axis>,
    /// Write the recording here [default: recordings/<session name>.rrd] (also with a viewer
    /// or a server: it keeps everything if the viewer goes away).
    #[arg(long, value_name = "PATH")]
    pub(crate) save: Option<PathBuf>,
    /// A viewer instead of the file.
    #[command(flatten)]
    pub(crate) viewer: ViewerArgs,
    /// Write per-step metrics (timings, counts, figures) as a JSON array.
    #[arg(long, value_name = "PATH")]
    pub(crate) metrics: Option<PathBuf>,
    /// Write the body and every mesh a step produces as OBJ files into this folder.
    #[arg(long, value_name = "DIR")]
    pub(crate) export: Option<PathBuf>,
    /// Write every step's pattern pieces into this folder: DXF (AAMA/ASTM layout, mm), SVG
    /// (1:1, mm), JSON (strain per piece, mismatch per seam) and one OBJ per piece (3D
    /// positions, 2D as vt). Cuts the pattern with the template's default seams when the
    /// session has no `patterns` statement.
    #[arg(long, value_name = "DIR")]
    pub(crate) patterns: Option<PathBuf>,
    /// Also log compute timings to the recording (makes recordings differ run to run).
    #[arg(long)]
    pub(crate) log_timings: bool,
    /// Log every patch of every garment mesh (M0, its clearance map, M1, their edges) and
    /// every curve at every step, also those the recording shows already, and clear what is
    /// already clear; by default a step sends only the patches and curves that changed. The
    /// scene at every step is the same either way.
    #[arg(long)]
    pub(crate) log_unchanged: bool,
    /// What the recording gets: every stage (all), the final meshes of each step (final), or
    /// the metrics and the log (metrics) [default: the session's `log detail=`, else all].
    #[arg(long, value_name = "DETAIL", value_parser = ["all", "final", "metrics"])]
    pub(crate) log_detail: Option<String>,
    /// Check every collision against the brute-force ground truth (every garment vertex
    /// and edge against every body triangle, every body edge against every garment face; a
    /// few seconds per step), and the step's quality
    /// check (partial by default) against a full one. The figures go to the log, the metrics
    /// and the progress lines.
    #[arg(long)]
    pub(crate) verify: bool,
    /// Test every vertex point-face against every body triangle (no partitions, no BVH, no
    /// line-line), to compare.
    #[arg(long)]
    pub(crate) brute_force: bool,
    /// Re-test every vertex each step (no inert points, no patch skipping), to compare.
    #[arg(long)]
    pub(crate) no_skipping: bool,
    /// Build M1 whole at every step: subdivide M0 again and collide every refined patch,
    /// nothing taken from the step before (the same M1, bit for bit, in more time), to
    /// compare.
    #[arg(long)]
    pub(crate) full_m1: bool,
    /// The quality check after each collision: `partial` measures only the vertices, edges
    /// and faces whose positions changed since they were last measured (the same figures),
    /// `full` measures everything every step. --verify runs a full check beside the
    /// step's own and says whether they agree.
    #[arg(long, value_name = "CHECK", default_value = "partial", value_parser = ["partial", "full"])]
    pub(crate) quality: String,
    /// Exit 1 when a step leaves the garment inside the body, crossing it or pierced by it
    /// after its collision, or refuses an edit (the run goes on and reports every one).
    #[arg(long)]
    pub(crate) strict: bool,
}

#[derive(Args, Debug)]
pub(crate) struct NurbsExperimentArgs {
    /// The accuracy wanted of the distance test, m: the recommended level is the least
    /// whose control-point distance is within it of the true distance.
    #[arg(long, value_name = "M", default_value_t = 0.0005)]
    pub(crate) accuracy: f64,
    /// Least subdivision level.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(0..=9))]
    pub(crate) min_level: u8,
    /// Greatest subdivision level (each level has 4 times the leaves of the one before).
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u8).range(0..=9))]
    pub(crate) max_level: u8,
    /// The butterfly (`.nurbs`, see assets/nurbs/README.md); default: the shipped one.
    #[arg(long, value_name = "FILE")]
    pub(crate) butterfly: Option<PathBuf>,
    /// The leaf (`.nurbs`); default: the shipped corn leaf.
    #[arg(long, value_name = "FILE")]
    pub(crate) leaf: Option<PathBuf>,
    /// Where the butterfly sits: leaf parameters u,v.
    #[arg(long, value_name = "U,V", value_delimiter = ',', num_args = 2, default_values_t = [0.6, 0.43])]
    pub(crate) at: Vec<f64>,
    /// The butterfly's turn about the leaf's normal, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 25.0, allow_negative_numbers = true)]
    pub(crate) yaw: f64,
    /// The butterfly's roll about its body, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 30.0, allow_negative_numbers = true)]
    pub(crate) roll: f64,
    /// The true distance at which the near pose holds the butterfly, m.
    #[arg(long, value_name = "M", default_value_t = 0.001)]
    pub(crate) distance: f64,
    /// Wall time over which each level's detection is repeated (the median is reported), ms.
    #[arg(long, value_name = "MS", default_value_t = 200.0)]
    pub(crate) timing_ms: f64,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Log both surfaces, the leaf hulls per level and the closest points to this recording.
    #[arg(long, value_name = "PATH", default_value = "recordings/nurbs-experiment.rrd")]
    pub(crate) save: PathBuf,
}

#[derive(Args, Debug)]
pub(crate) struct SculptCompareArgs {
    /// The body the garment is built on (OBJ, PLY, glTF or GLB; metres, y up, facing
    /// +z); default: the built-in body.
    #[arg(long, value_name = "MESH")]
    pub(crate) body: Option<PathBuf>,
    /// Sculpt this mesh (OBJ, PLY, glTF or GLB; metres) instead of the garment; --at must
    /// then be x,y,z.
    #[arg(long, value_name = "MESH", conflicts_with = "body")]
    pub(crate) mesh: Option<PathBuf>,
    /// Segments per anchor arc of the garment's M0.
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u16).range(2..=48))]
    pub(crate) resolution: u16,
    /// The pick: a control point of the jumpsuit (waist.front) or a point x,y,z (m).
    #[arg(
        long,
        value_name = "POINT",
        default_value = "waist.front",
        allow_hyphen_values = true
    )]
    pub(crate) at: String,
    /// Radius of the moved region, m.
    #[arg(long, value_name = "M", default_value_t = 0.08)]
    pub(crate) radius: f64,
    /// Offset of the pick along the surface normal, m (negative pushes in).
    #[arg(long, value_name = "M", default_value_t = 0.04, allow_negative_numbers = true)]
    pub(crate) peak: f64,
    /// Falloff: biweight, wendland or smoothstep.
    #[arg(long, default_value = "biweight")]
    pub(crate) falloff: String,
    /// Refine while a region face's longest edge exceeds this, m [default: the smaller of
    /// radius/4 and the region's longest edge before the drag].
    #[arg(long, value_name = "M")]
    pub(crate) eps: Option<f64>,
    /// Level limit of both subdivisions.
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u8).range(0..=8))]
    pub(crate) levels: u8,
    /// Loop's vertex-rule weight, 0 (interpolating) to 1 (Loop).
    #[arg(long, default_value_t = 1.0)]
    pub(crate) weight: f64,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Log the three results side by side to this recording.
    #[arg(long, value_name = "PATH", default_value = "recordings/sculpt-compare.rrd")]
    pub(crate) save: PathBuf,
}

#[derive(Args, Debug)]
pub(crate) struct MannequinArgs {
    /// Measured layers (rings) of the dress form.
    #[arg(long, default_value_t = 18, value_parser = clap::value_parser!(u16).range(4..=200))]
    pub(crate) layers: u16,
    /// Measured points per layer.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u16).range(6..=360))]
    pub(crate) points: u16,
    /// Split every grid interval this many ways (the paper: 6).
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u16).range(1..=20))]
    pub(crate) subdivisions: u16,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Log both surfaces, coloured by their distance to the true surface, to this recording.
    #[arg(long, value_name = "PATH", default_value = "recordings/mannequin.rrd")]
    pub(crate) save: PathBuf,
}
