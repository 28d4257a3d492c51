//! `check_hull` of crates/tumble/tests/fuzz_support: see there for the properties checked.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../crates/tumble/tests/fuzz_support/mod.rs"]
mod fuzz_support;

fuzz_target!(|input: fuzz_support::HullInput| fuzz_support::check_hull(&input));
