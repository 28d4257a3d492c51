//! Scene text: parsing and checking never panic; a scene that parses builds its world (or says
//! why not) without panicking. Meshes named by the scene come from a stub, never the disk.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../crates/tumble-io/tests/fuzz_support/mod.rs"]
mod fuzz_support;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        fuzz_support::check_scene_text(text);
    }
});
