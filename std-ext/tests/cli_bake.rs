//! `bvhkit bake` writes a file that opens in place and answers as the tree
//! it came from (binary, or 4-wide with `--wide` or `--quantized`); an
//! empty mesh bakes to the 32-byte header alone.

use bvhkit::layout::{QuantizedWide, Wide};
use bvhkit::{Aabb, Bvh, Pairs, TopDown};
use std::process::Command;

fn run(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args(args)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {text}{err}");
    text
}

#[test]
fn baked_files_open_and_answer_as_the_tree() {
    let dir = std::env::temp_dir().join(format!("bvhkit-cli-bake-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("rock.obj");
    let tris = bvhkit_std::scene::rock(3, 1);
    let mut obj = String::new();
    for t in &tris {
        for v in t.v {
            obj += &format!("v {} {} {}\n", v.x, v.y, v.z);
        }
    }
    for k in 0..tris.len() {
        obj += &format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3);
    }
    std::fs::write(&mesh, obj).unwrap();
    let tris = bvhkit_std::mesh::load(&mesh).unwrap();
    for kept in [false, true] {
        let out = dir.join(format!("rock-{kept}.bvhk"));
        let mut args = vec!["bake", mesh.to_str().unwrap(), "-o", out.to_str().unwrap()];
        if kept {
            args.push("--leaf-bounds");
        }
        let text = run(&args);
        assert!(text.contains("opened and validated again"), "{text}");
        let bytes = std::fs::read(&out).unwrap();
        assert!(text.contains(&format!("bytes {}\n", bytes.len())), "{text}");
        let mut seen = vec![0u32; Bvh::baked_seen_words(&bytes).unwrap()];
        let tree = Bvh::from_baked(&bytes, &mut seen).unwrap();
        assert_eq!(tree.leaf_bounds().is_some(), kept);
        let built = bvhkit_std::OwnedBvh::<Aabb>::build(&TopDown::default(), &tris).unwrap();
        assert_eq!(tree.nodes(), built.view().nodes());
        let count = |t: &Bvh<'_, Aabb>| Pairs::new(t, &tris, t, &tris).exact().count().unwrap();
        assert_eq!(count(&tree), count(&built.view()));
    }
    // The 4-wide layouts, with and without kept bounds: each opens in place
    // from 64-byte aligned memory, validates against the mesh and answers
    // as the binary tree.
    let built = bvhkit_std::OwnedBvh::<Aabb>::build(&TopDown::default(), &tris).unwrap();
    let want = Pairs::new(&built.view(), &tris, &built.view(), &tris)
        .exact()
        .count()
        .unwrap();
    for layout in ["--wide", "--quantized"] {
        for kept in [false, true] {
            let out = dir.join(format!("rock{layout}-{kept}.bvhk"));
            let (mesh, out_path) = (mesh.to_str().unwrap(), out.to_str().unwrap());
            let mut args = vec!["bake", mesh, "-o", out_path, layout];
            if kept {
                args.push("--leaf-bounds");
            }
            let text = run(&args);
            assert!(text.contains("opened and validated again"), "{text}");
            let bytes = std::fs::read(&out).unwrap();
            let mut store = Box::new(bvhkit::baked::Aligned([0u8; 1 << 16]));
            store.0[..bytes.len()].copy_from_slice(&bytes);
            let bytes = &store.0[..bytes.len()];
            let (records, has_kept, pairs) = if layout == "--wide" {
                let mut seen = vec![0u32; Wide::baked_seen_words(bytes).unwrap()];
                let w = Wide::from_baked(bytes, &mut seen).unwrap();
                w.validate(&tris).unwrap();
                let pairs = Pairs::new(&w, &tris, &w, &tris).exact().count().unwrap();
                (w.records().len(), w.leaf_bounds().is_some(), pairs)
            } else {
                let mut seen = vec![0u32; QuantizedWide::baked_seen_words(bytes).unwrap()];
                let q = QuantizedWide::from_baked(bytes, &mut seen).unwrap();
                q.validate(&tris).unwrap();
                let pairs = Pairs::new(&q, &tris, &q, &tris).exact().count().unwrap();
                (q.records().len(), q.leaf_bounds().is_some(), pairs)
            };
            assert_eq!(has_kept, kept);
            assert!(text.contains(&format!("records {records}\n")), "{text}");
            assert_eq!(pairs, want, "{layout}");
        }
    }
    // An empty scene is not bad input: a header and nothing else.
    let empty = dir.join("empty.obj");
    std::fs::write(&empty, "v 0 0 0\n").unwrap();
    let out = dir.join("empty.bvhk");
    run(&["bake", empty.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(
        std::fs::read(&out).unwrap().len(),
        bvhkit::baked::HEADER_BYTES
    );
    // A file that cannot be written: an error naming it, exit 1.
    let bad = dir.join("no-such-dir").join("x.bvhk");
    let status = Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args(["bake", mesh.to_str().unwrap(), "-o", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!status.status.success());
    assert!(String::from_utf8_lossy(&status.stderr).contains("no-such-dir"));
    std::fs::remove_dir_all(&dir).ok();
}
