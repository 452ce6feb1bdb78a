//! Real scanned meshes (fetched by `scripts/fetch-meshes` into `data/meshes/`):
//! each one loads, and the pair query of the mesh against a placed copy of
//! itself, on the canonical tree and on the 4-wide layout, equals brute force.
//! Skipped (with a message) when the meshes have not been fetched, so a fresh
//! `cargo test` passes without them.

use bvhkit::glam::Vec3;
use bvhkit::layout::{Wide, WideNode};
use bvhkit::{Aabb, Pairs, TopDown};
use bvhkit_std::mesh::{load, Placement};
use bvhkit_std::OwnedBvh;
use std::path::PathBuf;

#[test]
fn real_meshes_answer_like_brute_force() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../data/meshes");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("skipped: no {} (run scripts/fetch-meshes)", dir.display());
        return;
    };
    let mut checked = 0;
    for entry in entries.flatten() {
        let path = entry.path();
        let a = load(&path).unwrap_or_else(|e| panic!("{e}"));
        if a.len() > 25_000 {
            // The brute-force reference is quadratic in the contact region;
            // the large meshes are exercised by the benches instead.
            continue;
        }
        let bounds = a
            .iter()
            .fold(Aabb::EMPTY, |b, t| b.union(&bvhkit::Primitive::bounds(t)));
        let place = Placement {
            scale: 1.0,
            rotate_deg: Vec3::new(0.0, 7.0, 3.0),
            translate: bounds.extent() * 0.02,
        };
        let b = place.apply(&a).unwrap();
        let ta = OwnedBvh::<Aabb>::build(&TopDown::sah(), &a).unwrap();
        let tb = OwnedBvh::<Aabb>::build(&TopDown::sah(), &b).unwrap();
        let (va, vb) = (ta.view(), tb.view());
        let want = bvhkit_std::tour::reference_pairs(&a, &b);
        let mut got = Vec::new();
        Pairs::new(&va, &a, &vb, &b)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        got.sort_unstable();
        assert_eq!(got, want, "{}", path.display());
        let mut wa = vec![WideNode::EMPTY; Wide::records_needed(&va).unwrap()];
        let wa = Wide::from_bvh(&va, &mut wa).unwrap();
        assert_eq!(Pairs::new(&wa, &a, &vb, &b).count().unwrap(), want.len());
        checked += 1;
    }
    eprintln!("checked {checked} real meshes");
}
