//! Puts the board's memory map where cortex-m-rt's `link.x` looks for
//! `memory.x` (a file of that name in the package root would shadow it),
//! and, for the `baked` set, builds both objects' trees on the host and
//! bakes them into `OUT_DIR` (`a.bvhk`, `b.bvhk`) for `include_bytes!`.
use std::{env, fs, path::PathBuf};

use bvhkit::{Aabb, Node, TopDown, Triangle};

#[allow(dead_code)] // the host uses the objects only
#[path = "src/scene.rs"]
mod scene;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    fs::copy("mps2-an386.x", out.join("memory.x")).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=mps2-an386.x");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/scene.rs");
    for (which, name) in [(0, "a.bvhk"), (1, "b.bvhk")] {
        let zero = Triangle::new(Default::default(), Default::default(), Default::default());
        let mut tris = [zero; scene::N];
        scene::object(which, &mut tris);
        let mut nodes = vec![Node::<Aabb>::ZERO; bvhkit::max_nodes(scene::N)];
        let mut index = vec![0u32; scene::N];
        let tree = TopDown::sah()
            .build(&tris, &mut nodes, &mut index)
            .expect("the demo scene builds");
        let mut bytes = vec![0u8; tree.baked_len()];
        tree.bake(&mut bytes).expect("sized by baked_len");
        fs::write(out.join(name), bytes).unwrap();
    }
}
