//! Figures of the book's `embedded.md` chapter: the footprint bars, parsed
//! at draw time from the recorded table (`measured/embedded-footprint.md`,
//! written by `scripts/embedded-demo`) and the budget that script holds the
//! minimal set to.

use super::performance::{linear_ticks, Pic};
use super::svg::{colour, Style};
use super::{Figure, FigureError};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    Ok(vec![footprint(book_src)?])
}

/// One feature set's row of the recorded footprint table.
struct Set {
    name: String,
    flash: u64,
    flash_over: u64,
    stack: u64,
    stack_over: u64,
}

/// The rows of the table's first part (feature set, flash, flash over
/// baseline, static RAM, stack, stack over baseline, soft-double
/// routines), and its stamp line.
fn recorded(book_src: &Path) -> Result<(Vec<Set>, String), FigureError> {
    let path = book_src.join("measured/embedded-footprint.md");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| FigureError(format!("{}: {e}", path.display())))?;
    let mut sets = Vec::new();
    for line in text.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        // "| a | b | ... |" splits into an empty cell at each end.
        if cells.len() != 9 {
            continue;
        }
        let nums: Vec<u64> = cells[2..8].iter().filter_map(|c| c.parse().ok()).collect();
        if nums.len() != 6 {
            continue; // the header and its rule
        }
        sets.push(Set {
            name: cells[1].to_string(),
            flash: nums[0],
            flash_over: nums[1],
            stack: nums[3],
            stack_over: nums[4],
        });
    }
    if sets.len() < 2 || sets[0].name != "baseline" {
        return Err(FigureError(format!(
            "{}: no footprint table starting with the baseline",
            path.display()
        )));
    }
    let stamp = text.lines().next().unwrap_or_default();
    let stamp = stamp
        .split(" by ")
        .next()
        .unwrap_or_default()
        .trim_end_matches(':')
        .to_string();
    Ok((sets, stamp))
}

/// `NAME=$((A * B))` or `NAME=N` in the demo script: the budget CI checks.
fn budget(script: &str, name: &str) -> Option<u64> {
    let line = script
        .lines()
        .find_map(|l| l.trim().strip_prefix(&format!("{name}=")))?;
    let expr = line.trim_start_matches("$((").trim_end_matches("))");
    expr.split('*')
        .map(|f| f.trim().parse::<u64>().ok())
        .product()
}

fn footprint(book_src: &Path) -> Result<Figure, FigureError> {
    let (sets, stamp) = recorded(book_src)?;
    let script_path = book_src.join("../../scripts/embedded-demo");
    let script = std::fs::read_to_string(&script_path)
        .map_err(|e| FigureError(format!("{}: {e}", script_path.display())))?;
    let no_budget = |n: &str| FigureError(format!("{}: no {n}", script_path.display()));
    let flash_budget = budget(&script, "FLASH_BUDGET").ok_or_else(|| no_budget("FLASH_BUDGET"))?;
    let stack_budget = budget(&script, "STACK_BUDGET").ok_or_else(|| no_budget("STACK_BUDGET"))?;
    let base = &sets[0];
    let rows = &sets[1..];
    const KIB: f64 = 1024.0;

    let (w, row_h, top) = (880.0, 26.0, 76.0);
    let h = top + row_h * rows.len() as f32 + 52.0;
    let mut pic = Pic::new(w, h);
    pic.text(
        w * 0.5,
        16.0,
        14.0,
        "middle",
        "What bvhkit adds to the firmware, per feature set (KiB over the baseline)",
    );
    let stamp = stamp.replacen("Recorded", "recorded", 1);
    pic.text(
        w * 0.5,
        33.0,
        11.0,
        "middle",
        &format!(
            "baseline firmware: {} B flash, {} B stack · {stamp}",
            base.flash, base.stack
        ),
    );
    let names_right = 165.0;
    // Two bar panels, flash and stack, each with its budget line and a
    // column of values on its right.
    let panels = [
        (
            "flash over baseline",
            names_right + 10.0,
            480.0,
            flash_budget,
            50.0,
            rows.iter().map(|s| s.flash_over).collect::<Vec<_>>(),
        ),
        (
            "stack high-water over baseline",
            560.0,
            w - 60.0,
            stack_budget,
            2.0,
            rows.iter().map(|s| s.stack_over).collect::<Vec<_>>(),
        ),
    ];
    let bottom = top + row_h * rows.len() as f32;
    for (i, s) in rows.iter().enumerate() {
        let y = top + row_h * (i as f32 + 0.5);
        pic.text(names_right, y, 11.0, "end", &s.name);
    }
    for (title, left, right, budget, step, values) in panels {
        let max = values.iter().copied().max().unwrap_or(0).max(budget) as f64 / KIB;
        let scale_max = (max / step).ceil() * step;
        let px = |kib: f64| left + (right - left) * (kib / scale_max) as f32;
        pic.text((left + right) * 0.5, top - 24.0, 12.0, "middle", title);
        for t in linear_ticks(0.0, scale_max, step) {
            let x = px(t);
            pic.line((x, top), (x, bottom), Style::line("#e4e4e4").width(0.8));
            pic.text(x, bottom + 11.0, 10.5, "middle", &format!("{t:.0}"));
        }
        pic.text((left + right) * 0.5, bottom + 28.0, 11.0, "middle", "KiB");
        pic.line(
            (left, top),
            (left, bottom),
            Style::line("#444444").width(1.0),
        );
        pic.text(right + 44.0, top - 8.0, 10.5, "end", "KiB");
        for (i, (&v, s)) in values.iter().zip(rows).enumerate() {
            let y = top + row_h * i as f32 + 5.0;
            let c = match s.name.as_str() {
                "minimal" => colour(0),
                n if n.starts_with("minimal,") => colour(4),
                "typical" => colour(1),
                "boxes" => colour(2),
                _ => colour(3),
            };
            let kib = v as f64 / KIB;
            pic.rect(
                left,
                y,
                px(kib) - left,
                row_h - 10.0,
                Style::filled(c, 0.85).width(0.8),
            );
            pic.text(
                right + 44.0,
                y + (row_h - 10.0) * 0.5,
                10.5,
                "end",
                &format!("{kib:.1}"),
            );
        }
        let bx = px(budget as f64 / KIB);
        let red = colour(5);
        pic.line(
            (bx, top - 4.0),
            (bx, bottom + 2.0),
            Style::line(red).width(1.6).dashed(),
        );
        pic.text(
            bx,
            top - 10.0,
            10.5,
            "middle",
            &format!("budget {:.0} KiB", budget as f64 / KIB),
        );
    }
    Ok(Figure {
        name: "embedded-footprint",
        chapter: "embedded.md",
        svg: pic.finish(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_are_read_like_the_script_computes_them() {
        let script = "X=1\nFLASH_BUDGET=$((64 * 1024))\nSTACK_BUDGET=6144\n";
        assert_eq!(budget(script, "FLASH_BUDGET"), Some(65_536));
        assert_eq!(budget(script, "STACK_BUDGET"), Some(6_144));
        assert_eq!(budget(script, "NONE"), None);
    }
}
