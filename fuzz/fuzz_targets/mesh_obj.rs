//! The obj loader on arbitrary bytes: an error or triangles, never a panic.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| bvhkit_fuzz::load_as("obj", data));
