//! The grader: named checks with points, run on any [`Exercises`] implementation.
//!
//! Checks are chosen to reject the plausible wrong answers, not only to accept
//! the right one: strict comparisons on touching boxes, a fit that starts from
//! the origin, a sphere that misses a point by rounding, a partition along a
//! fixed axis, and so on.

mod common;
mod ex01_aabb_overlap;
mod ex02_fit_and_merge;
mod ex03_object_median;
mod ex04_larger_volume;
mod ex05_recursive_pairs;
mod ex06_stack_pairs;
mod ex07_cost_function;
mod ex08_bottom_up;
mod ex09_refit;
mod ex10_insertion_cost;
mod ex11_implicit_array;
mod ex12_preorder;
mod ex13_quantize;
mod ex14_static_sizing;
mod ex15_workload_pareto;
mod ex16_sah_bins;
mod ex17_kdop;
mod ex18_descent_rules;
mod ex19_partition_criteria;
mod ex20_bfs_dfs;
mod ex21_obb_overlap;
mod ex22_best_first_nearest;
mod ex23_leaf_order;
mod ex24_stop_and_fall_back;
mod ex25_fit_unit_costs;
mod ex26_axis_and_split;
mod ex27_tree_measures;
mod ex28_tri_nodes;
mod ex29_fit_obb;
mod ex30_preorder_offsets;
mod ex31_collision_system;
mod ex32_insertion_descent;
mod ex33_ray_best_first;
mod ex34_wide_nodes;
mod ex35_top_down_build;
mod ex36_short_links;
mod ex37_merged_leaves;
mod ex38_clip_polygon;
mod ex39_relocate_pieces;
mod ex40_leaf_collapse;
mod ex41_box_triangle;
mod ex42_self_pairs;
mod ex43_closest_pair;
mod ex44_crossing_segment;
mod ex45_penetration;
mod ex46_handles;
mod ex47_within;
mod ex48_rebuild;
mod ex49_baked;
mod ex50_frame_box;
mod ex51_sphere_cast;
mod ex52_area_rotation;
mod ex53_bins_and_partition;
#[cfg(test)]
mod wrong;

use crate::Exercises;
use std::panic::{self, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::Duration;

/// One check: a name, its points, and the test.
#[derive(Clone, Copy)]
pub struct Check {
    /// Exercise number it belongs to.
    pub exercise: u32,
    /// What it checks.
    pub name: &'static str,
    /// Points it is worth.
    pub points: u32,
    /// The test.
    pub run: fn(&dyn Exercises) -> bool,
}

impl std::fmt::Debug for Check {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Check({} {})", self.exercise, self.name)
    }
}

/// Titles of the exercises.
pub const EXERCISES: [(u32, &str); 53] = [
    (1, "AABB overlap"),
    (2, "AABB and sphere: fit and merge"),
    (3, "top-down partition: object median"),
    (4, "descent rule: descend the larger volume"),
    (5, "informed depth-first traversal (recursive)"),
    (6, "traversal with a fixed stack"),
    (7, "the cost function T"),
    (8, "bottom-up construction: greedy merges"),
    (9, "refit after motion"),
    (10, "insertion: the cost of a candidate sibling"),
    (11, "implicit array: index arithmetic"),
    (12, "preorder layout: convert a tree"),
    (13, "quantize a box conservatively"),
    (14, "sizing static buffers"),
    (
        15,
        "the advisor's yardstick: workload time and the Pareto front",
    ),
    (16, "the surface area heuristic over a row of bins"),
    (17, "14-DOPs: fit and overlap"),
    (
        18,
        "descent rules: A first, simultaneous, alternate, by overlap",
    ),
    (19, "partition criteria of a top-down split"),
    (20, "breadth-first and depth-first visiting order"),
    (21, "oriented boxes: the separating-axis test"),
    (22, "best-first search: the nearest primitive"),
    (23, "primitive bounds in leaf order"),
    (24, "stopping and falling back"),
    (25, "fitting unit costs to measured queries"),
    (26, "axis choice and split point"),
    (27, "measuring a tree: depth, leaf depth, SAH cost"),
    (28, "tri-nodes: records and wasted slots"),
    (29, "oriented boxes: fit with given axes"),
    (30, "offsets instead of pointers: preorder links"),
    (31, "the collision system: broad phase, then narrow phase"),
    (32, "insertion: where a new object goes, and the order"),
    (33, "best-first search for a ray: the closest hit"),
    (34, "tree degree: collapsing into 4-wide nodes"),
    (35, "a whole top-down build, into the caller's arrays"),
    (36, "16-bit links with an escape to a far table"),
    (
        37,
        "fuller quantized records: a small subtree as one leaf slot",
    ),
    (38, "exact k-DOP measures: polygon clipping"),
    (39, "the parallel build: moving pieces into place"),
    (40, "leaf collapse: the cheapest cut of a bottom-up tree"),
    (
        41,
        "box against triangle, exactly: separating axes by signs",
    ),
    (
        42,
        "self-collision: one tree against itself, each pair once",
    ),
    (43, "the closest pair of two trees: branch and bound"),
    (44, "where two triangles cross: the shared segment"),
    (45, "how deep two boxes or two spheres overlap"),
    (46, "handles that cannot lie: generations on a free list"),
    (47, "within a distance: broad phase, then narrow phase"),
    (48, "rebuilding a dynamic tree in place: the median split"),
    (
        49,
        "opening a baked tree: what to check before trusting bytes",
    ),
    (
        50,
        "entering the world: a box in a local frame, rounded outward",
    ),
    (51, "sweeping a ball: the time of impact against a triangle"),
    (
        52,
        "rotating by area: the swap that shrinks a dynamic tree most",
    ),
    (53, "bins and the partition that must agree with them"),
];

/// A score for one exercise.
#[derive(Clone, Debug, PartialEq)]
pub struct ExerciseScore {
    /// Exercise number.
    pub exercise: u32,
    /// Title.
    pub title: &'static str,
    /// Points earned.
    pub earned: u32,
    /// Points possible.
    pub possible: u32,
    /// Names of the checks that failed (or panicked).
    pub failed: Vec<String>,
}

/// All checks of all exercises, in exercise order.
pub fn checks() -> Vec<Check> {
    [
        ex01_aabb_overlap::checks(),
        ex02_fit_and_merge::checks(),
        ex03_object_median::checks(),
        ex04_larger_volume::checks(),
        ex05_recursive_pairs::checks(),
        ex06_stack_pairs::checks(),
        ex07_cost_function::checks(),
        ex08_bottom_up::checks(),
        ex09_refit::checks(),
        ex10_insertion_cost::checks(),
        ex11_implicit_array::checks(),
        ex12_preorder::checks(),
        ex13_quantize::checks(),
        ex14_static_sizing::checks(),
        ex15_workload_pareto::checks(),
        ex16_sah_bins::checks(),
        ex17_kdop::checks(),
        ex18_descent_rules::checks(),
        ex19_partition_criteria::checks(),
        ex20_bfs_dfs::checks(),
        ex21_obb_overlap::checks(),
        ex22_best_first_nearest::checks(),
        ex23_leaf_order::checks(),
        ex24_stop_and_fall_back::checks(),
        ex25_fit_unit_costs::checks(),
        ex26_axis_and_split::checks(),
        ex27_tree_measures::checks(),
        ex28_tri_nodes::checks(),
        ex29_fit_obb::checks(),
        ex30_preorder_offsets::checks(),
        ex31_collision_system::checks(),
        ex32_insertion_descent::checks(),
        ex33_ray_best_first::checks(),
        ex34_wide_nodes::checks(),
        ex35_top_down_build::checks(),
        ex36_short_links::checks(),
        ex37_merged_leaves::checks(),
        ex38_clip_polygon::checks(),
        ex39_relocate_pieces::checks(),
        ex40_leaf_collapse::checks(),
        ex41_box_triangle::checks(),
        ex42_self_pairs::checks(),
        ex43_closest_pair::checks(),
        ex44_crossing_segment::checks(),
        ex45_penetration::checks(),
        ex46_handles::checks(),
        ex47_within::checks(),
        ex48_rebuild::checks(),
        ex49_baked::checks(),
        ex50_frame_box::checks(),
        ex51_sphere_cast::checks(),
        ex52_area_rotation::checks(),
        ex53_bins_and_partition::checks(),
    ]
    .concat()
}

/// How long one check may run before it scores 0 (a loop that never ends
/// costs only that check's points; the reference answers need well under a
/// second per check even unoptimised).
pub const CHECK_TIME_LIMIT: Duration = Duration::from_secs(10);

/// Runs every check on `e`; a check that fails, panics or runs past
/// [`CHECK_TIME_LIMIT`] scores 0, and the others are still graded.
pub fn grade(e: &'static (dyn Exercises + Sync)) -> Vec<ExerciseScore> {
    grade_each(e, CHECK_TIME_LIMIT, |_| {})
}

/// [`grade`] with a time limit per check, calling `done` with each
/// exercise's score as soon as its checks have run (so that a long or stuck
/// exercise does not hide the results before it).
pub fn grade_each(
    e: &'static (dyn Exercises + Sync),
    limit: Duration,
    done: impl FnMut(&ExerciseScore),
) -> Vec<ExerciseScore> {
    let all: Vec<u32> = EXERCISES.iter().map(|&(n, _)| n).collect();
    grade_exercises(e, &all, limit, done)
}

/// [`grade_each`] for the exercises numbered in `exercises` only (the
/// `grade --exercise N` command), their scores in exercise order. Numbers
/// that name no exercise are ignored: [`exercise_title`] tells them apart.
pub fn grade_exercises(
    e: &'static (dyn Exercises + Sync),
    exercises: &[u32],
    limit: Duration,
    mut done: impl FnMut(&ExerciseScore),
) -> Vec<ExerciseScore> {
    quiet_checks();
    let mut scores: Vec<ExerciseScore> = EXERCISES
        .iter()
        .filter(|(n, _)| exercises.contains(n))
        .map(|&(exercise, title)| ExerciseScore {
            exercise,
            title,
            earned: 0,
            possible: 0,
            failed: vec![],
        })
        .collect();
    for s in &mut scores {
        for c in checks().iter().filter(|c| c.exercise == s.exercise) {
            s.possible += c.points;
            match run_check(c, e, limit) {
                Ok(()) => s.earned += c.points,
                Err(why) => s.failed.push(why),
            }
        }
        done(s);
    }
    scores
}

/// The title of exercise `n`, `None` if there is no such exercise.
pub fn exercise_title(n: u32) -> Option<&'static str> {
    EXERCISES.iter().find(|&&(x, _)| x == n).map(|&(_, t)| t)
}

/// Installs, once, a panic hook that records where a check panicked
/// (instead of printing it) on the grader's check threads, and leaves every
/// other thread's panics to the hook that was there before. Installed for
/// good rather than swapped per run, so that runs on several threads (the
/// tests) cannot leave the quiet hook behind.
fn quiet_checks() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            let is_check = std::thread::current()
                .name()
                .is_some_and(|n| n.starts_with(CHECK_THREAD));
            if is_check {
                let at = info.location().map(|l| (l.file().to_string(), l.line()));
                PANIC_AT.with(|p| *p.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
    });
}

/// The name prefix of the threads checks run on.
const CHECK_THREAD: &str = "grader check ";

thread_local! {
    /// Where the last panic on this thread happened (file, line).
    static PANIC_AT: std::cell::RefCell<Option<(String, u32)>> = const { std::cell::RefCell::new(None) };
}

/// Runs one check on its own thread, so that one that never returns can be
/// abandoned after `limit`. `Err` says why it scored 0.
fn run_check(c: &Check, e: &'static (dyn Exercises + Sync), limit: Duration) -> Result<(), String> {
    let (tx, rx) = mpsc::channel();
    let run = c.run;
    let spawned = std::thread::Builder::new()
        .name(format!("{CHECK_THREAD}{} {}", c.exercise, c.name))
        .spawn(move || {
            common::take_explanation();
            let out = panic::catch_unwind(AssertUnwindSafe(|| run(e)));
            let out = out.map(|passed| (passed, common::take_explanation()));
            let out = out.map_err(|p| {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                (msg, PANIC_AT.with(|at| at.borrow_mut().take()))
            });
            // The receiver is gone if the check ran past its limit.
            let _ = tx.send(out);
        });
    if let Err(err) = spawned {
        return Err(format!("{} (could not start: {err})", c.name));
    }
    match rx.recv_timeout(limit) {
        Ok(Ok((true, _))) => Ok(()),
        Ok(Ok((false, None))) => Err(c.name.to_string()),
        Ok(Ok((false, Some(why)))) => Err(format!("{}: {why}", c.name)),
        Ok(Err((msg, at))) => Err(format!("{} (panicked{}: {msg})", c.name, where_(at))),
        Err(_) => Err(format!(
            "{} (did not finish within {} s: a loop that never ends?)",
            c.name,
            limit.as_secs_f64()
        )),
    }
}

/// " in `method` at student.rs:LINE" when the panic happened in a student's
/// answer (the method found from the source), else " at FILE:LINE".
fn where_(at: Option<(String, u32)>) -> String {
    let Some((file, line)) = at else {
        return String::new();
    };
    if file.ends_with("student.rs") {
        if let Some(method) = enclosing_fn(include_str!("../student.rs"), line) {
            return format!(" in your `{method}` at student.rs:{line}");
        }
    }
    format!(" at {file}:{line}")
}

/// The name of the last `fn` declared at or before `line` (1-based) of `source`.
fn enclosing_fn(source: &str, line: u32) -> Option<&str> {
    source
        .lines()
        .take(line as usize)
        .filter_map(|l| {
            let rest = l.trim_start().strip_prefix("fn ")?;
            rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
        })
        .last()
}

/// The header line of the table [`report`] prints.
pub fn report_header() -> String {
    format!("{:<4} {:<44} {:>8}\n", "#", "exercise", "points")
}

/// One exercise's lines of the table: its score, then each failed check.
pub fn report_exercise(x: &ExerciseScore) -> String {
    let mut s = format!(
        "{:<4} {:<44} {:>8}\n",
        x.exercise,
        x.title,
        format!("{}/{}", x.earned, x.possible)
    );
    for f in &x.failed {
        s += &format!("       - failed: {f}\n");
    }
    s
}

/// The last line of the table: `total: E/P points (X%)`.
pub fn report_total(scores: &[ExerciseScore]) -> String {
    let (e, p): (u32, u32) = scores
        .iter()
        .fold((0, 0), |(e, p), x| (e + x.earned, p + x.possible));
    format!(
        "total: {e}/{p} points ({}%)\n",
        (e * 100).checked_div(p).unwrap_or(0)
    )
}

/// The table the `grade` command prints; the last line is `total: E/P points (X%)`.
pub fn report(scores: &[ExerciseScore]) -> String {
    let mut s = report_header();
    for x in scores {
        s += &report_exercise(x);
    }
    s + &report_total(scores)
}

#[cfg(test)]
mod tests {
    use super::wrong::{Wrong, LOOPS, PANICS};
    use super::*;
    use crate::reference::Reference;
    use crate::student::Student;

    #[test]
    fn reference_scores_everything() {
        for s in grade(&Reference) {
            assert_eq!(s.earned, s.possible, "{s:?}");
        }
        assert!(report(&grade(&Reference)).ends_with("total: 575/575 points (100%)\n"));
    }

    /// A never-returning answer scores 0 on its own checks only, after the
    /// time limit, and every other exercise is graded (and reported as it
    /// is done) as if nothing happened.
    #[test]
    fn a_looping_answer_costs_only_its_own_checks() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong {
            exercise: 8,
            k: LOOPS,
        }));
        let mut reported = Vec::new();
        let start = std::time::Instant::now();
        let scores = grade_each(e, Duration::from_secs(2), |x| reported.push(x.exercise));
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{:?}",
            start.elapsed()
        );
        assert_eq!(reported, EXERCISES.iter().map(|e| e.0).collect::<Vec<_>>());
        for s in &scores {
            if s.exercise == 8 {
                assert_eq!(s.earned, 0, "{s:?}");
                assert!(
                    s.failed
                        .iter()
                        .all(|f| f.contains("did not finish within 2 s")),
                    "{s:?}"
                );
            } else {
                assert_eq!(s.earned, s.possible, "{s:?}");
            }
        }
    }

    /// A failed check says what went in, what was expected and what came
    /// back: the strict comparison on touching boxes, in exercise 1.
    #[test]
    fn a_failure_says_what_went_in_and_what_came_back() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong { exercise: 1, k: 1 }));
        let s = grade_exercises(e, &[1], CHECK_TIME_LIMIT, |_| {});
        assert_eq!(s.len(), 1);
        assert!(
            s[0].failed.contains(
                &"touching faces, edges and corners overlap: aabb_overlaps([min (0, 0, 0), \
                  max (1, 1, 1)], [min (1, 0, 0), max (2, 1, 1)]) returned false, expected true"
                    .to_string()
            ),
            "{s:?}"
        );
    }

    /// `grade --exercise N`: only the exercises asked for, in order, each
    /// with all its checks.
    #[test]
    fn grading_some_exercises_grades_only_those() {
        let all = grade(&Reference);
        let some = grade_exercises(&Reference, &[31, 2, 99], CHECK_TIME_LIMIT, |_| {});
        assert_eq!(some, vec![all[1].clone(), all[30].clone()]);
        assert_eq!(exercise_title(99), None);
        assert_eq!(exercise_title(1), Some("AABB overlap"));
    }

    /// A panic in an answer names where it happened and its message; the
    /// other checks are graded.
    #[test]
    fn a_panicking_answer_is_named_with_its_message() {
        let e: &'static Wrong = Box::leak(Box::new(Wrong {
            exercise: 11,
            k: PANICS,
        }));
        let s = &grade(e)[10];
        assert!(s.exercise == 11 && s.earned < s.possible, "{s:?}");
        assert!(
            s.failed.iter().any(|f| f.contains("panicked at ")
                && f.contains("ex11_implicit_array.rs:")
                && f.ends_with(": a slip)")),
            "{s:?}"
        );
        assert_eq!(grade(e)[0].earned, grade(e)[0].possible);
    }

    /// The method around a line of the student's file is found from its source.
    #[test]
    fn a_panic_in_the_students_file_names_the_method() {
        let src = "impl X {\n    fn first(&self) {\n        a();\n    }\n    fn second_one(&self) -> u32 {\n        b()\n    }\n}\n";
        assert_eq!(enclosing_fn(src, 3), Some("first"));
        assert_eq!(enclosing_fn(src, 6), Some("second_one"));
        assert_eq!(enclosing_fn(src, 1), None);
        assert_eq!(where_(None), "");
        assert_eq!(
            where_(Some(("core/src/x.rs".into(), 7))),
            " at core/src/x.rs:7"
        );
        let student = include_str!("../student.rs");
        let line = student
            .lines()
            .position(|l| l.contains("fn descend_a"))
            .unwrap() as u32
            + 2;
        assert_eq!(
            where_(Some(("exercises/src/student.rs".into(), line))),
            format!(" in your `descend_a` at student.rs:{line}")
        );
    }

    /// Every wrong answer kept with an exercise loses points on that
    /// exercise, and each exercise keeps at least five of them.
    #[test]
    fn plausible_wrong_answers_lose_points() {
        let counts = super::wrong::counts();
        assert_eq!(counts.len(), EXERCISES.len());
        let few: Vec<_> = counts.iter().filter(|&&(_, n)| n < 5).collect();
        assert!(
            few.is_empty(),
            "exercises with fewer than 5 wrong answers: {few:?}"
        );
        let names: Vec<&str> = checks().iter().map(|c| c.name).collect();
        let (mut full_marks, mut unexplained) = (Vec::new(), Vec::new());
        for (exercise, count) in counts {
            for k in 1..=count {
                // Leaked: each check runs on a thread that may outlive the call.
                let e: &'static Wrong = Box::leak(Box::new(Wrong { exercise, k }));
                let s = &grade_exercises(e, &[exercise], CHECK_TIME_LIMIT, |_| {})[0];
                if s.earned >= s.possible {
                    full_marks.push((exercise, k));
                }
                // A failure that is only the check's name tells the student
                // nothing about the input, the expected and the returned.
                for f in &s.failed {
                    if names.contains(&f.as_str()) {
                        unexplained.push((exercise, k, f.clone()));
                    }
                }
            }
        }
        assert!(
            full_marks.is_empty(),
            "wrong answers (exercise, k) with full marks: {full_marks:?}"
        );
        assert!(
            unexplained.is_empty(),
            "failures without an explanation (exercise, wrong answer, check): {unexplained:?}"
        );
    }

    #[test]
    fn untouched_stubs_score_zero_without_stopping_the_grader() {
        // Meaningful only while the stubs are untouched; students who start
        // filling them in will see this test fail, which is the point.
        if std::env::var_os("BVHKIT_STUDENT").is_some() {
            return;
        }
        let scores = grade(&Student);
        assert_eq!(scores.len(), EXERCISES.len());
        assert!(
            scores.iter().all(|s| s.earned == 0 && s.possible > 0),
            "the exercise stubs in exercises/src/student.rs are no longer untouched. If you \
             are working on the exercises, this is expected: run the tests with \
             BVHKIT_STUDENT=1 to skip this check (see the book's exercises chapter), and \
             `cargo run -p bvhkit-exercises --bin grade` for your score. Scores now: {:?}",
            scores
                .iter()
                .map(|s| (s.exercise, s.earned))
                .collect::<Vec<_>>()
        );
    }
}
