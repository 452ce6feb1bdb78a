//! `cargo run -p bvhkit-exercises --bin grade [-- --reference] [--exercise N]...`
//!
//! Prints each exercise's score as soon as it is graded, with what went in,
//! what was expected and what came back for each failed check; a check that
//! runs past the time limit scores 0 and the others are still graded.
//! `--exercise N` (repeatable) grades exercise N only.

use bvhkit_exercises::{grader, reference::Reference, student::Student, Exercises};
use std::io::Write;

const USAGE: &str = "usage: grade [--reference] [--exercise N]...";

fn main() {
    let mut reference = false;
    let mut only = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--reference" => reference = true,
            "--exercise" | "-e" => match args.next().map(|n| (n.parse::<u32>(), n)) {
                Some((Ok(n), _)) if grader::exercise_title(n).is_some() => only.push(n),
                Some((_, n)) => fail(&format!(
                    "there is no exercise {n:?}: the exercises are numbered 1 to {}",
                    grader::EXERCISES[grader::EXERCISES.len() - 1].0
                )),
                None => fail("--exercise needs a number"),
            },
            "--help" | "-h" => {
                println!("{USAGE}");
                return;
            }
            other => fail(&format!("unknown argument {other:?}")),
        }
    }
    if only.is_empty() {
        only = grader::EXERCISES.iter().map(|&(n, _)| n).collect();
    }
    let e: &'static (dyn Exercises + Sync) = if reference { &Reference } else { &Student };
    println!(
        "grading the {} answers (at most {} s per check)\n",
        if reference { "reference" } else { "student" },
        grader::CHECK_TIME_LIMIT.as_secs()
    );
    print!("{}", grader::report_header());
    let scores = grader::grade_exercises(e, &only, grader::CHECK_TIME_LIMIT, |x| {
        print!("{}", grader::report_exercise(x));
        let _ = std::io::stdout().flush();
    });
    print!("{}", grader::report_total(&scores));
    // A check abandoned past its time limit may still be running: leave now.
    std::process::exit(0);
}

fn fail(why: &str) -> ! {
    eprintln!("grade: {why}\n{USAGE}");
    std::process::exit(2);
}
