use std::time::Instant;
use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::*;
use drape::garment::*;

fn main() {
    let mesh = BodyMesh::load(&BodySource::Builtin, 1.0).unwrap();
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).unwrap();
    let probe = BodyProbe::new(&body.mesh.mesh).unwrap();
    let t = Instant::now();
    let index = BodyIndex::new(&body, &SliceOptions::default());
    println!("index {:?} in {:?}", index, t.elapsed());
    for s in index.slices.slices.iter().step_by(25) {
        println!("slice y {:.3} loops {} centres {:?}", s.y, s.loops.len(), s.centres.map(|c| (c.choice, c.convexity, c.width)));
    }
    let mut dims = Dimensions::default();
    let args: Vec<String> = std::env::args().collect();
    if args.len() > 2 { dims.values.insert(args[1].clone(), args[2].parse().unwrap()); }
    let fw = build_framework(&body, &probe, TemplateKind::Jumpsuit, &dims, &FrameworkOptions::default()).unwrap();
    let g = GarmentMesh::from_framework(&fw, index.height);
    let mut state = DetectState::default();
    let t = Instant::now();
    let c = collide(&index, &g, fw.ease(), &CollisionOptions::default(), &mut state);
    println!("collide {:?}: hits {} tested {} by_method {:?}", t.elapsed(), c.detection.hits.len(), c.detection.tested, c.detection.by_method);
    let mut rules = std::collections::BTreeMap::new();
    for r in &c.responses { *rules.entry(r.rule.name()).or_insert(0) += 1; }
    println!("rules {:?}", rules);
    let parts: Vec<_> = c.detection.hits.iter().map(|h| index.partitions[h.partition].id.letter()).collect();
    let mut pc = std::collections::BTreeMap::new();
    for p in parts { *pc.entry(p).or_insert(0) += 1; }
    println!("hits per partition {:?}", pc);
    println!("quality {:?}", serde_json::to_string(&c.quality).unwrap());
    let t = Instant::now();
    let before = quality(&index, &g.mesh.positions, &g.edges, &[]);
    println!("quality before {:?} in {:?}", serde_json::to_string(&before).unwrap(), t.elapsed());
    let t = Instant::now();
    let gt = ground_truth(&body.mesh.mesh, &g.mesh.positions, &g.edges);
    println!("truth before: inside {} crossing {} in {:?}", gt.inside_count(), gt.crossing_count(), t.elapsed());
    let detected: std::collections::BTreeSet<u32> = c.detection.hits.iter().map(|h| h.vertex).collect();
    let missed = (0..gt.inside.len()).filter(|&v| gt.inside[v] && !detected.contains(&(v as u32))).count();
    let false_hits = detected.iter().filter(|&&v| !gt.inside[v as usize]).count();
    println!("missed {missed} false {false_hits}");
    let gt2 = ground_truth(&body.mesh.mesh, &c.mesh.positions, &g.edges);
    println!("truth after: inside {} crossing {}", gt2.inside_count(), gt2.crossing_count());
    for r in &c.responses { println!("resp v{} {:?} from {:.4?} to {:.4?} err {:e}", r.vertex, r.rule, r.from, r.to, r.ease_error); }
    for acc in [Acceleration::BruteForce, Acceleration::Partitioned, Acceleration::PartitionedBvh] {
        let mut o = DetectOptions::default(); o.acceleration = acc;
        for m in [None, Some(drape::body::DetectionMethod::PointFace)] {
            o.method_override = m;
            let t = Instant::now();
            let d = detect(&index, &g.input(), &o, &mut DetectState::default());
            println!("{acc:?} {m:?}: {:?} hits {}", t.elapsed(), d.hits.len());
        }
    }
    let t = Instant::now();
    let n: usize = g.mesh.positions.iter().filter(|p| index.nearest(**p, 0.3).is_some()).count();
    println!("nearest all {n}: {:?}", t.elapsed());
    let t = Instant::now();
    let n: usize = g.edges.iter().filter(|[a,b]| index.segment_hits(g.mesh.positions[*a as usize], g.mesh.positions[*b as usize])).count();
    println!("edges {n}: {:?}", t.elapsed());
    for &e in &c.quality.crossing { let [a,b] = g.edges[e as usize]; let pa = c.mesh.positions[a as usize]; let pb = c.mesh.positions[b as usize];
      println!("cross e{e} {a}-{b} {:.4?} {:.4?} d {:.4} {:.4} len {:.4} parts {:?}", pa, pb, index.signed_distance(pa, 1.0).unwrap(), index.signed_distance(pb,1.0).unwrap(), pa.distance(pb), (c.detection.partition[a as usize], c.detection.partition[b as usize])); }
    // Second step unchanged: skipping
    let t = Instant::now();
    let c2 = collide(&index, &g, fw.ease(), &CollisionOptions::default(), &mut state);
    println!("again {:?}: tested {} inert {} patch {}", t.elapsed(), c2.detection.tested, c2.detection.skipped_inert, c2.detection.skipped_patch);
}
#[allow(dead_code)]
fn unused() {}
