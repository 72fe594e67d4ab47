//! Edits that cannot be honoured are refused with the limit they break, and the session goes
//! on with the garment as it was; a step that leaves the garment inside or crossing the body
//! says so loudly; `--strict` turns both into exit code 1.

use drape::session::{
    ConstraintStage, GarmentStage, RunOptions, Shortfall, SinkError, StageInfo, StageSink, parse_session, run_session,
};

/// The refusals, by step.
#[derive(Default)]
struct Refusals(Vec<(usize, String)>);

impl StageSink for Refusals {
    fn garment(&mut self, info: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Refused { message, .. } = stage {
            self.0.push((info.step, message.to_string()));
        }
        Ok(())
    }

    fn constraints(&mut self, info: &StageInfo, stage: ConstraintStage<'_>) -> Result<(), SinkError> {
        if let ConstraintStage::Refused { message, .. } = stage {
            self.0.push((info.step, message.to_string()));
        }
        Ok(())
    }
}

#[test]
fn impossible_edits_are_refused_naming_the_limit_and_the_session_goes_on() {
    let text = "drape 1\ngarment jumpsuit resolution=3\nset waist_girth 100\ndrag left_knee by=0,2,0\n\
                drag crotch.point by=0,0.3,0\nset inseam 3\ndrag left_knee by=0,0.02,0\nundo\nundo\n";
    let session = parse_session(text, "refusals.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = Refusals::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    let said: Vec<(usize, &str)> = sink.0.iter().map(|(s, m)| (*s, m.as_str())).collect();
    assert_eq!(said.len(), 4, "{said:?}");
    assert_eq!(said[0].0, 2);
    assert!(
        said[0].1.starts_with(
            "ring 'waist': girth 100.0000 m is more than 4 times the body's tape girth there (0.6519 m): at most 2.6078 m"
        ),
        "{}",
        said[0].1
    );
    assert_eq!(said[1].0, 3);
    assert!(
        said[1].1.starts_with("ring 'left_knee' dragged to y = 2.4")
            && said[1].1.contains("would leave its band")
            && said[1].1.contains("between left_hem.front and left_thigh.front"),
        "{}",
        said[1].1
    );
    assert_eq!(said[2].0, 4);
    assert!(
        said[2].1.starts_with("'crotch.point' would end ") && said[2].1.contains("inside the body"),
        "{}",
        said[2].1
    );
    assert_eq!(said[3].0, 5);
    assert!(
        said[3]
            .1
            .starts_with("dimension inseam = 3: the hem must lie between the knee and the foot")
    );
    // The session went on: the last drag was made, and the undos take back it, then the
    // refused inseam (which changes nothing).
    let refused: Vec<usize> = report
        .shortfalls
        .iter()
        .filter_map(|(s, f)| matches!(f, Shortfall::Refused(_)).then_some(*s))
        .collect();
    assert_eq!(refused, vec![2, 3, 4, 5]);
    assert_eq!(report.steps.len(), 9);
    assert!(
        report.steps[6].figures.contains_key("passes"),
        "the last drag was solved"
    );
    for k in [2, 3, 4, 5] {
        assert!(report.steps[k].figures.contains_key("refused"), "step {k}");
    }
}

/// Without edge rounds, edges of the new garment cross the body: a new garment has
/// nothing to fall back on, so it is kept and reported loudly (a guarantee shortfall, a red
/// mark, a WARN line); an edit that leaves edges crossing (the tight ease) is refused and
/// the garment stays as it was.
#[test]
fn a_step_that_leaves_the_garment_in_the_body_says_so_and_strict_fails_the_run() {
    let text = "drape 1\ngarment jumpsuit resolution=3\nset ease 0.003\n";
    let session = parse_session(text, "unmet.drape", std::path::Path::new(".")).expect("parses");
    let mut options = RunOptions::default();
    options.collision.response.edge_rounds = 0;
    let (rec, storage) = drape::viz::target::memory_recording("unmet").unwrap();
    let report = {
        let mut logger = drape::viz::RerunLogger::new(rec, drape::viz::LogOptions::default()).unwrap();
        run_session(&session, &options, &mut [&mut logger])
    };
    assert!(report.error.is_none(), "{:?}", report.error);
    let unmet: Vec<(usize, usize, usize)> = report
        .shortfalls
        .iter()
        .filter_map(|(s, f)| match f {
            Shortfall::Guarantee { inside, crossing, .. } => Some((*s, *inside, *crossing)),
            Shortfall::Refused(_) | Shortfall::Layers(_) => None,
        })
        .collect();
    assert_eq!(
        unmet.iter().map(|u| u.0).collect::<Vec<_>>(),
        vec![1],
        "the new garment without edge rounds left nothing crossing, or the edit was not refused"
    );
    let refused = report.steps[2].figures["refused"].as_str().unwrap_or_default();
    assert!(
        refused.starts_with("the garment cannot be kept clear of the body after this edit"),
        "{refused}"
    );
    assert_eq!(report.steps[2].figures["guarantee_met"], false);
    for (step, inside, crossing) in &unmet {
        let m = &report.steps[*step];
        assert_eq!(m.figures["guarantee_met"], false);
        assert_eq!(m.figures["crossing_edges"], *crossing);
        assert_eq!(m.figures["penetrating_vertices"], *inside);
    }
    // In the recording: a red mark at `collision/guarantee` and a WARN line.
    let summary = super::snapshot::summarize(storage.take());
    let mark: Vec<&str> = summary
        .split("\n/")
        .filter(|block| block.starts_with("collision/guarantee\n"))
        .collect();
    assert!(mark.len() == 1 && mark[0].contains("  Points3D:colors"), "{summary}");
    assert!(summary.contains("GUARANTEE NOT MET"), "{summary}");
    assert!(summary.contains("WARN"), "{summary}");
}

/// The binary: a refused edit exits 0, or 1 with `--strict`, which names it.
#[test]
fn strict_turns_a_refusal_into_exit_code_1() {
    let dir = std::env::temp_dir().join(format!("drape-strict-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("s.drape");
    std::fs::write(&session, "drape 1\ngarment dress resolution=2\nset waist_girth 100\n").unwrap();
    let rrd = dir.join("s.rrd");
    let args = ["run", session.to_str().unwrap(), "--save", rrd.to_str().unwrap()];
    let (code, stderr) = super::session_errors::drape(&args);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("note: step 2: edit refused: ring 'waist'"), "{stderr}");
    let (code, stderr) = super::session_errors::drape(&[&args[..], &["--strict"]].concat());
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("error: step 2: edit refused: ring 'waist'"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The last framework a garment stage showed.
#[derive(Default)]
struct LastFramework(Option<drape::garment::Framework>);

impl StageSink for LastFramework {
    fn garment(&mut self, _: &StageInfo, stage: GarmentStage<'_>) -> Result<(), SinkError> {
        if let GarmentStage::Part(fw, _) = stage {
            self.0 = Some(fw.clone());
        }
        Ok(())
    }
}

/// A hem ring dragged sideways off its leg is refused naming the section it would leave;
/// one dragged 1 cm is not. The truth, from the body's own vertices: at the hem's height the
/// leg inside the ring (the body vertices within 5 mm of that height, between the ring's
/// left and right ends) lies wholly to one side of the ring moved by 0.3 m, and within it
/// moved by 1 cm.
#[test]
fn a_hem_dragged_off_its_leg_is_refused_naming_the_section_it_leaves() {
    let text = "drape 1\ngarment jumpsuit resolution=3\n";
    let session = parse_session(text, "hem.drape", std::path::Path::new(".")).expect("parses");
    let mut last = LastFramework::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut last]);
    assert!(report.error.is_none(), "{:?}", report.error);
    let fw = last.0.expect("a garment");
    let hem: Vec<glam::DVec3> = fw
        .control_points()
        .into_iter()
        .filter(|(n, _)| n.starts_with("left_hem."))
        .map(|(_, p)| p)
        .collect();
    assert!(hem.len() >= 4, "{hem:?}");
    let y = hem.iter().map(|p| p.y).sum::<f64>() / hem.len() as f64;
    let (lo, hi) = hem
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.x), h.max(p.x)));
    let body = super::common::real_body();
    let leg: Vec<f64> = body
        .mesh
        .mesh
        .positions
        .iter()
        .filter(|p| (p.y - y).abs() < 0.005 && p.x > lo && p.x < hi)
        .map(|p| p.x)
        .collect();
    assert!(leg.len() >= 5, "the leg at y = {y}: {leg:?}");
    let (leg_lo, leg_hi) = leg
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| (l.min(x), h.max(x)));
    let (far, near) = (0.3, 0.01);
    assert!(lo + far > leg_hi, "moved by {far} m the ring lies beside the leg");
    assert!(
        lo + near < leg_lo && hi + near > leg_hi,
        "moved by {near} m it is still around it"
    );
    let text = format!("{text}drag left_hem by={far},0,0\ndrag left_hem by={near},0,0\n");
    let session = parse_session(&text, "hem.drape", std::path::Path::new(".")).expect("parses");
    let mut sink = Refusals::default();
    let report = run_session(&session, &RunOptions::default(), &mut [&mut sink]);
    assert!(report.error.is_none(), "{:?}", report.error);
    assert_eq!(sink.0.len(), 1, "{:?}", sink.0);
    let (step, message) = &sink.0[0];
    assert_eq!(*step, 2);
    assert!(
        message.starts_with("ring 'left_hem' dragged by (0.300, 0.000, 0.000) m would no longer go around the body")
            && message.contains("so the garment would pass through the body"),
        "{message}"
    );
}
