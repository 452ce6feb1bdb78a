//! The book's chapters as doctests: `cargo test -p bvhkit-book` compiles and
//! runs every Rust block, and a failure names `book/src/<chapter>.md (line N)`.
//! Prose-only blocks are fenced as `text` or `console`.

macro_rules! chapters {
    ($($name:ident => $file:literal),* $(,)?) => {
        $(
            #[cfg(doctest)]
            #[doc = include_str!(concat!("src/", $file))]
            pub mod $name {}
        )*
        /// Every chapter file, so a test can check that none is left out.
        pub const CHAPTERS: &[&str] = &[$($file),*];
    };
}

chapters! {
    introduction => "introduction.md",
    bounding_volumes => "bounding-volumes.md",
    characteristics => "characteristics.md",
    tree_degree => "tree-degree.md",
    top_down => "top-down.md",
    bottom_up => "bottom-up.md",
    insertion => "insertion.md",
    traversal => "traversal.md",
    descent_rules => "descent-rules.md",
    collision_system => "collision-system.md",
    representations => "representations.md",
    robustness => "robustness.md",
    performance => "performance.md",
    embedded => "embedded.md",
    exercises => "exercises.md",
}

#[cfg(test)]
mod tests {
    /// Every chapter listed in SUMMARY.md is compiled here, and vice versa.
    #[test]
    fn summary_and_doctests_list_the_same_chapters() {
        let summary = include_str!("src/SUMMARY.md");
        for file in super::CHAPTERS {
            assert!(
                summary.contains(&format!("({file})")),
                "{file} missing from SUMMARY.md"
            );
        }
        let linked = summary.matches(".md)").count();
        assert_eq!(
            linked,
            super::CHAPTERS.len(),
            "SUMMARY.md links a chapter the doctest crate does not include"
        );
    }

    /// The recorded peer run the performance chapter includes is there, is
    /// stamped (date, machine, peers) and shows only checked, exact answers.
    #[test]
    fn recorded_peer_run_is_complete_and_exact() {
        let chapter = include_str!("src/performance.md");
        assert!(chapter.contains("{{#include measured/peers.md}}"));
        let run = include_str!("src/measured/peers.md");
        let stamp = run
            .lines()
            .find(|l| l.contains(" UTC · "))
            .expect("stamp line");
        assert!(stamp.contains("cores") && stamp.contains("parry3d") && stamp.contains("obvhs"));
        let rows: Vec<&str> = run
            .lines()
            .skip_while(|l| !l.starts_with("#### Every tree"))
            .filter(|l| l.starts_with("| ") && !l.starts_with("| mesh"))
            .collect();
        for krate in ["bvhkit", "parry3d", "obvhs", "bvh"] {
            assert!(
                rows.iter().any(|r| r.contains(&format!("| {krate} |"))),
                "{krate}"
            );
        }
        for r in &rows {
            assert!(
                r.trim_end().ends_with("| exact |"),
                "not checked exact: {r}"
            );
        }
        assert!(!run.contains("WRONG"));
    }
}
