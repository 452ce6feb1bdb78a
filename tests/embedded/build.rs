//! Puts the board's memory map where cortex-m-rt's `link.x` looks for
//! `memory.x` (a file of that name in the package root would shadow it).
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    fs::copy("mps2-an386.x", out.join("memory.x")).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=mps2-an386.x");
    println!("cargo:rerun-if-changed=build.rs");
}
