//! A recording file is written uncompressed and without Rerun's index during the session
//! (`drape::viz::session_file`) and compressed and indexed when it is closed
//! (`drape::viz::rrd_index`). The truth is Rerun's own decoder: it reads the footer's
//! manifests back, and the messages of both files.

use std::path::{Path, PathBuf};

use drape::viz::replay::read_rrd;
use drape::viz::rrd_index::index_into;
use drape::viz::{RecordingTarget, open_recording};
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::LogMsg;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drape-rrd-index-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// The data messages of the file, and the chunks its footer's manifests list (Rerun's
/// decoder reads the footer at the end of the stream).
fn decoded(path: &Path) -> (usize, usize) {
    let bytes = std::fs::read(path).expect("read the recording");
    let mut decoder = DecoderApp::decode_eager(bytes.as_slice()).expect("a recording");
    let mut data = 0;
    for msg in decoder.by_ref() {
        if let LogMsg::ArrowMsg(id, _) = msg.expect("every message decodes")
            && id.is_recording()
        {
            data += 1;
        }
    }
    let manifests = decoder.rrd_manifests().expect("the manifests decode");
    let listed = manifests
        .iter()
        .filter(|m| m.store_id.is_recording())
        .map(|m| m.data.num_rows())
        .sum();
    (data, listed)
}

/// Logs `steps` steps of a moving point cloud to `path`, as a session does, and closes it.
fn record(path: &Path, steps: i64) {
    let rec = open_recording(&RecordingTarget::File(path.to_path_buf()), "rrd-index-test").expect("open");
    for step in 0..steps {
        rec.set_time_sequence("step", step);
        let points: Vec<[f32; 3]> = (0..50).map(|k| [k as f32, step as f32, 0.5]).collect();
        rec.log("garment/points", &rerun::Points3D::new(points)).expect("log");
        rec.log("log", &rerun::TextLog::new(format!("step {step}")))
            .expect("log");
        // A step's end: its chunks go to the file (drape's logger sends each as it comes).
        rec.flush_blocking().expect("flush");
    }
    drop(rec);
}

/// The file a session writes has no manifest until it is closed; indexed, it lists every
/// chunk of the recording, and holds the very messages the session wrote.
#[test]
fn a_recording_is_indexed_when_closed_with_every_chunk_and_the_same_messages() {
    let dir = scratch("indexed");
    let (partial, done) = (dir.join("run.rrd.partial"), dir.join("run.rrd"));
    record(&partial, 7);
    let (data, listed) = decoded(&partial);
    assert!(data >= 14, "{data} data messages");
    assert_eq!(listed, 0, "written without an index during the session");
    let before = read_rrd(&partial).expect("the partial file reads");
    index_into(&partial, &done).expect("indexed");
    assert!(!partial.exists(), "the partial file is removed");
    assert_eq!(
        decoded(&done),
        (data, data),
        "every data chunk is in the footer's manifest"
    );
    assert_eq!(read_rrd(&done).expect("the indexed file reads"), before);
    std::fs::remove_dir_all(&dir).ok();
}

/// A file that is not a recording is refused with its name, and nothing is lost: the file
/// stays where it was, the target is not written, and no half-written file is left.
#[test]
fn a_file_that_does_not_decode_is_left_as_it_was() {
    let dir = scratch("broken");
    let (partial, done) = (dir.join("run.rrd.partial"), dir.join("run.rrd"));
    std::fs::write(&partial, b"not a recording at all").expect("write");
    let err = index_into(&partial, &done).expect_err("refused");
    assert!(err.to_string().contains("run.rrd"), "{err}");
    assert_eq!(std::fs::read(&partial).expect("kept"), b"not a recording at all");
    assert!(!done.exists());
    let left: Vec<_> = std::fs::read_dir(&dir)
        .expect("list")
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(left.len(), 1, "{left:?}");
    std::fs::remove_dir_all(&dir).ok();
}
