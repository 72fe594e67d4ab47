//! What Rerun's encoding and writing cost drape per chunk, measured in one run.
//!
//! `taskset -c 0 cargo bench --bench logging` logs chunks of Points3D of several sizes into
//! an `.rrd` file, two ways: Rerun's `log` then a flush of the batcher per call (how drape
//! logged before its recordings sent chunks themselves), and a chunk built by the caller and
//! sent past the batcher (`send_chunk`, how drape's `OrderedRecording` logs now). Each time
//! is the whole cost of a call on the core: building, encoding, compressing and writing the
//! chunk, up to the end of a blocking flush. Sent chunks are timed twice: into Rerun's file
//! sink (its writer thread compresses each chunk and adds it to the file's index) and into
//! the file a drape session writes (`viz::session_file`: uncompressed, unindexed, compressed
//! and indexed once when closed). It prints us per chunk and ns per byte of positions,
//! medians of 5 runs; on one core the per-chunk part is what makes a garment mesh logged as
//! hundreds of small entities slower than as a few large ones.

use std::time::Instant;

use rerun::log::{Chunk, RowId};

/// The cost of `n` calls logging `size` points each, us per call: through the batcher
/// (`batched`) or as chunks sent directly.
fn per_call_us(rec: &rerun::RecordingStream, n: usize, size: usize, batched: bool) -> f64 {
    let points: Vec<[f32; 3]> = (0..size).map(|i| [i as f32, 0.5 * i as f32, 1.0]).collect();
    let start = Instant::now();
    for k in 0..n {
        let path = format!("bench/{size}/{}", k % 50);
        let data = rerun::Points3D::new(points.iter().copied());
        if batched {
            rec.log(path, &data).expect("log");
            rec.flush_async().expect("flush");
        } else {
            let chunk = Chunk::builder(path)
                .with_archetype(RowId::new(), rec.now(), &data)
                .build()
                .expect("chunk");
            rec.send_chunk(chunk);
        }
    }
    rec.flush_blocking().expect("flush");
    start.elapsed().as_secs_f64() * 1e6 / n as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let dir = std::env::temp_dir().join(format!("drape-bench-logging-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let rec = drape::viz::open_file_recording(&dir.join("rerun.rrd"), "bench", drape::viz::default_blueprint())
        .expect("recording");
    let session = drape::viz::open_recording(
        &drape::viz::RecordingTarget::File(dir.join("session.rrd")),
        "bench-session",
    )
    .expect("recording");
    rec.set_time_sequence("step", 1);
    session.set_time_sequence("step", 1);
    println!(
        "| points per chunk | chunks | log + flush, us/chunk | sent chunk, us/chunk | sent chunk, ns/byte | sent into a session's file, us/chunk | ns/byte |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for (size, n) in [(10usize, 1000usize), (1_000, 400), (10_000, 100), (100_000, 20)] {
        let batched = median((0..5).map(|_| per_call_us(&rec, n, size, true)).collect());
        let sent = median((0..5).map(|_| per_call_us(&rec, n, size, false)).collect());
        let own = median((0..5).map(|_| per_call_us(&session, n, size, false)).collect());
        let bytes = (12 * size) as f64;
        println!(
            "| {size} | {n} | {batched:.1} | {sent:.1} | {:.2} | {own:.1} | {:.2} |",
            sent * 1e3 / bytes,
            own * 1e3 / bytes
        );
    }
    drop((rec, session));
    std::fs::remove_dir_all(&dir).ok();
}
