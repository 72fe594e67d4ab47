use drape::body::{Body, BodyMesh, BodySource, LandmarkOptions, PartitionOptions};
use drape::collision::*;
use drape::garment::*;
fn main() {
    let mesh = BodyMesh::load(&BodySource::Builtin, 1.0).unwrap();
    let body = Body::analyse(mesh, &LandmarkOptions::default(), &PartitionOptions::default()).unwrap();
    let probe = BodyProbe::new(&body.mesh.mesh).unwrap();
    let index = BodyIndex::new(&body, &SliceOptions::default());
    let mut dims = Dimensions::default();
    dims.values.insert("waist_girth".into(), 0.8096);
    dims.values.insert("ease".into(), 0.004);
    let fw = build_framework(&body, &probe, TemplateKind::Jumpsuit, &dims, &FrameworkOptions::default()).unwrap();
    let g = GarmentMesh::from_framework(&fw, index.height);
    let c = collide(&index, &g, fw.ease(), &CollisionOptions::default(), &mut DetectState::default());
    println!("rounds {:?} crossing {}", c.edge_rounds, c.quality.crossing_edges);
    let names = &fw.m0.patch_names;
    for &e in &c.quality.crossing {
        let [a, b] = g.edges[e as usize];
        let (pa, pb) = (c.mesh.positions[a as usize], c.mesh.positions[b as usize]);
        let pn: Vec<&String> = g.vertex_patches[a as usize].iter().map(|&k| &names[k as usize]).collect();
        println!("e{e} {a}-{b} {:.3?} {:.3?} d {:.4} {:.4} len {:.3} {:?} moved {:?}", pa, pb, index.signed_distance(pa,1.0).unwrap(), index.signed_distance(pb,1.0).unwrap(), pa.distance(pb), pn,
          c.responses.iter().filter(|r| r.vertex == a || r.vertex == b).map(|r| (r.vertex, r.rule, r.edge_round)).collect::<Vec<_>>());
    }
    let worst = c.responses.iter().max_by(|x, y| x.ease_error.abs().total_cmp(&y.ease_error.abs())).unwrap();
    println!("worst ease {:?}", worst);
}
