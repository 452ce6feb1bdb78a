//! The `grade` command as a student runs it: the reference answers score
//! every point, the untouched stubs none, and the last line says so in the
//! form CI reads. (Building the command here also lets CI run the very
//! binary the tests built instead of compiling it once more.)

use std::process::Command;

fn last_line(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_grade"))
        .args(args)
        .output()
        .expect("grade runs");
    assert!(out.status.success(), "grade {args:?} failed: {out:?}");
    let stdout = String::from_utf8(out.stdout).expect("grade prints UTF-8");
    stdout.lines().last().unwrap_or_default().to_string()
}

/// `total: EARNED/POSSIBLE points (PERCENT%)`, parsed.
fn total(line: &str) -> (u32, u32, u32) {
    let parse = || -> Option<(u32, u32, u32)> {
        let rest = line.strip_prefix("total: ")?;
        let (earned, rest) = rest.split_once('/')?;
        let (possible, rest) = rest.split_once(" points (")?;
        let percent = rest.strip_suffix("%)")?;
        Some((
            earned.parse().ok()?,
            possible.parse().ok()?,
            percent.parse().ok()?,
        ))
    };
    parse().unwrap_or_else(|| panic!("not a total line: {line:?}"))
}

#[test]
fn reference_answers_score_every_point() {
    let (earned, possible, percent) = total(&last_line(&["--reference"]));
    assert!(possible > 0);
    assert_eq!((earned, percent), (possible, 100));
}

#[test]
fn untouched_stubs_score_nothing() {
    // A student filling in the stubs skips this, as the unit test does.
    if std::env::var_os("BVHKIT_STUDENT").is_some() {
        return;
    }
    let (earned, possible, percent) = total(&last_line(&[]));
    assert!(possible > 0);
    assert_eq!((earned, percent), (0, 0));
}

#[test]
fn a_single_exercise_is_graded_alone() {
    let (earned, possible, _) = total(&last_line(&["--reference", "--exercise", "1"]));
    let (_, all, _) = total(&last_line(&["--reference"]));
    assert!(0 < possible && possible < all && earned == possible);
}
