//! One-process A/B of the quantized 4-wide layout's merge limit
//! (`QuantizedWide::from_bvh_merged`): records, bytes per triangle, depth,
//! pair-query and ray medians per limit, on the peer benchmark's scene (the
//! mesh's boxes against a copy turned by 0.02 rad and shifted by 1%, the
//! default builder, no kept leaf bounds). Every limit must give the same
//! answers. Rounds alternate the limits; the second round is printed.
//!
//! Run: `MERGES=0,8 cargo run --release -p bvhkit-std --features cli --example quantized_merge -- data/meshes/*.off`
use bvhkit::glam::Vec3;
use bvhkit::layout::{QuantNode, QuantizedWide};
use bvhkit::{Aabb, Hierarchy, Pairs, Primitive, Query, RayOrder, TopDown, Triangle};
use bvhkit_std::{layouts::rays, median_time, mesh, scene, OwnedBvh};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let merges: Vec<u32> = std::env::var("MERGES")
        .unwrap_or("0,8".into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    for path in &args {
        let a: Vec<Triangle> = mesh::load(std::path::Path::new(path)).unwrap();
        let ba: Vec<Aabb> = a.iter().map(Primitive::bounds).collect();
        let bounds = ba.iter().fold(Aabb::EMPTY, |acc, b| {
            Aabb::new(acc.min.min(b.min), acc.max.max(b.max))
        });
        let shift = (bounds.max - bounds.min) * Vec3::new(0.01, 0.007, 0.004);
        let b = scene::transformed(&a, 0.02, shift);
        let bb: Vec<Aabb> = b.iter().map(Primitive::bounds).collect();
        let ta = OwnedBvh::<Aabb>::build(&TopDown::default(), &ba).unwrap();
        let tb = OwnedBvh::<Aabb>::build(&TopDown::default(), &bb).unwrap();
        let (va, vb) = (ta.plain_view(), tb.plain_view());
        let rs = rays(&a, 20_000);
        let n = a.len();
        let mut recs: Vec<(u32, Vec<QuantNode>, Vec<QuantNode>)> = Vec::new();
        for &m in &merges {
            let mut ra =
                vec![QuantNode::EMPTY; QuantizedWide::records_needed_merged(&va, m).unwrap()];
            let mut rb =
                vec![QuantNode::EMPTY; QuantizedWide::records_needed_merged(&vb, m).unwrap()];
            QuantizedWide::from_bvh_merged(&va, m, &mut ra).unwrap();
            QuantizedWide::from_bvh_merged(&vb, m, &mut rb).unwrap();
            recs.push((m, ra, rb));
        }
        let mut want = None;
        for round in 0..2 {
            for (m, ra, rb) in recs.iter_mut() {
                let qa = QuantizedWide::from_bvh_merged(&va, *m, ra).unwrap();
                let qb = QuantizedWide::from_bvh_merged(&vb, *m, rb).unwrap();
                let (tp, np) = median_time(9, || Pairs::new(&qa, &ba, &qb, &bb).count().unwrap());
                let (tr, nr) = median_time(3, || {
                    rs.iter()
                        .map(|r| {
                            qa.cast_ray(&a, r, RayOrder::default(), ())
                                .unwrap()
                                .map(|h| h.prim as u64)
                                .unwrap_or(0)
                        })
                        .sum::<u64>()
                });
                if *want.get_or_insert((np, nr)) != (np, nr) {
                    panic!("answers differ");
                }
                if round == 1 {
                    println!(
                        "{:<28} n {n:>7} merge {m:>2}: records {:>6} B/tri {:>6.2} (records {:>5.2}) slots/rec {:.2} depth {:>2} pairs {:>8.3} ms rays {:>8.3} ms",
                        path.rsplit('/').next().unwrap(), qa.records().len(), qa.bytes() as f64 / n as f64,
                        (qa.records().len() * 64) as f64 / n as f64,
                        (qa.node_count() - 1) as f64 / (qa.records().len() - 1) as f64, qa.depth(),
                        tp.as_secs_f64() * 1e3, tr.as_secs_f64() * 1e3
                    );
                }
            }
        }
    }
}
