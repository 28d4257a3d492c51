//! The parser fuzz targets (`fuzz/fuzz_targets/{scene_parse,obj_read,stl_read}.rs`) as proptests,
//! so stable `cargo test` runs them: the same checks (`fuzz_support`) on the example scenes with
//! random edits, on OBJ text assembled from OBJ-like tokens, and on STL bytes with a valid or
//! broken binary layout. Crashes the fuzzers found are kept below as `fuzz_regression_*` tests.

mod fuzz_support;

use fuzz_support::{check_obj, check_scene_text, check_stl};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

const SCENES: [&str; 6] = [
    include_str!("../../../scenes/stack.toml"),
    include_str!("../../../scenes/shapes.toml"),
    include_str!("../../../scenes/pendulum.toml"),
    include_str!("../../../scenes/playground.toml"),
    include_str!("../../../scenes/bouncing_balls.toml"),
    include_str!("../../../scenes/incline.toml"),
];

/// Pieces that keep an edited scene close to valid TOML, so the edits reach the checks.
const SCENE_TOKENS: [&str; 24] = [
    "0",
    "-1",
    "1e308",
    "-1e-320",
    "nan",
    "inf",
    "[",
    "]",
    "{",
    "}",
    ",",
    "=",
    "\n",
    "\"",
    "[[body]]",
    "[[joint]]",
    "[world]",
    "type = \"hinge\"",
    "kind = \"static\"",
    "shape = { type = \"mesh\", file = \"cube.obj\" }",
    "half_extents = [0.0, 1.0, 1.0]",
    "radius = -1",
    "dt = 0",
    "body_a = \"box 0\"",
];

/// An edit: at a fraction of the text, delete some bytes and insert a token.
fn edit() -> impl Strategy<Value = (f64, usize, usize)> {
    (0.0..1.0f64, 0..8usize, 0..SCENE_TOKENS.len())
}

fn apply(text: &str, edits: &[(f64, usize, usize)]) -> String {
    let mut s = text.to_string();
    for &(at, delete, token) in edits {
        let mut i = (at * s.len() as f64) as usize;
        while !s.is_char_boundary(i) {
            i -= 1;
        }
        let mut j = (i + delete).min(s.len());
        while !s.is_char_boundary(j) {
            j += 1;
        }
        s.replace_range(i..j, SCENE_TOKENS[token]);
    }
    s
}

const OBJ_TOKENS: [&str; 16] =
    ["v", "f", "vn", "vt", "o", "g", " ", "\n", "1", "-1", "0", "2/3", "1//1", "1e400", "nan", "#"];

fn stl_binary() -> impl Strategy<Value = Vec<u8>> {
    (0..6u32, proptest::collection::vec(any::<f32>(), 0..72), any::<bool>()).prop_map(
        |(count, floats, lie)| {
            let mut bytes = vec![0u8; 80];
            let claimed = if lie { count + 3 } else { count };
            bytes.extend_from_slice(&claimed.to_le_bytes());
            for t in 0..count as usize {
                for k in 0..12 {
                    let x = floats.get(t * 12 + k).copied().unwrap_or(k as f32);
                    bytes.extend_from_slice(&x.to_le_bytes());
                }
                bytes.extend_from_slice(&[0, 0]);
            }
            bytes
        },
    )
}

proptest! {
    // A fixed seed: the same cases on every run, so a rare find cannot make CI flaky; the fuzzers
    // are what explores.
    #![proptest_config(Config { cases: 256, rng_seed: RngSeed::Fixed(0x9a25_e125), ..Config::default() })]

    #[test]
    fn edited_scenes_never_panic(scene in 0..SCENES.len(), edits in proptest::collection::vec(edit(), 1..6)) {
        check_scene_text(&apply(SCENES[scene], &edits));
    }

    #[test]
    fn random_scene_text_never_panics(text in ".{0,400}") {
        check_scene_text(&text);
    }

    #[test]
    fn obj_like_text_never_panics(tokens in proptest::collection::vec(0..OBJ_TOKENS.len(), 0..200)) {
        let text: String = tokens.iter().map(|&t| OBJ_TOKENS[t]).collect::<Vec<_>>().join(" ");
        check_obj(&text);
    }

    #[test]
    fn random_obj_text_never_panics(text in "[vf0-9 ./\\-\\n]{0,300}") {
        check_obj(&text);
    }

    #[test]
    fn stl_bytes_never_panic(bytes in stl_binary()) {
        check_stl(&bytes);
    }

    #[test]
    fn random_stl_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        check_stl(&bytes);
        let mut ascii = b"solid x\n".to_vec();
        ascii.extend_from_slice(&bytes);
        check_stl(&ascii);
    }
}

#[test]
fn the_cube_stub_mesh_is_a_valid_closed_mesh() {
    let mesh = tumble_io::obj_from_str(fuzz_support::CUBE_OBJ, std::path::Path::new("cube.obj")).unwrap();
    assert!(tumble::Shape::TriMesh(mesh).mass_properties(1000.0).is_ok());
}
