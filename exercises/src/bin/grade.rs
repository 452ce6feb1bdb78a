//! `cargo run -p bvhkit-exercises --bin grade [-- --reference]`

use bvhkit_exercises::{grader, reference::Reference, student::Student, Exercises};

fn main() {
    let reference = std::env::args().skip(1).any(|a| a == "--reference");
    let e: &dyn Exercises = if reference { &Reference } else { &Student };
    println!(
        "grading the {} answers\n",
        if reference { "reference" } else { "student" }
    );
    print!("{}", grader::report(&grader::grade(e)));
}
