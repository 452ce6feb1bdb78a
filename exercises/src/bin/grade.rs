//! `cargo run -p bvhkit-exercises --bin grade [-- --reference]`
//!
//! Prints each exercise's score as soon as it is graded; a check that runs
//! past the time limit scores 0 and the others are still graded.

use bvhkit_exercises::{grader, reference::Reference, student::Student, Exercises};
use std::io::Write;

fn main() {
    let reference = std::env::args().skip(1).any(|a| a == "--reference");
    let e: &'static (dyn Exercises + Sync) = if reference { &Reference } else { &Student };
    println!(
        "grading the {} answers (at most {} s per check)\n",
        if reference { "reference" } else { "student" },
        grader::CHECK_TIME_LIMIT.as_secs()
    );
    print!("{}", grader::report_header());
    let scores = grader::grade_each(e, grader::CHECK_TIME_LIMIT, |x| {
        print!("{}", grader::report_exercise(x));
        let _ = std::io::stdout().flush();
    });
    print!("{}", grader::report_total(&scores));
    // A check abandoned past its time limit may still be running: leave now.
    std::process::exit(0);
}
