//! The `bvhkit` command-line tool.

use bvhkit::build::PRESETS;
use bvhkit::Descent;
use bvhkit_std::collide::{self, CollideOptions, Input, Mode, TRAVERSALS, VOLUMES};
use bvhkit_std::tour::{self, TourOptions};
use clap::builder::PossibleValuesParser;
use clap::{Parser, Subcommand, ValueEnum};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "bvhkit",
    version,
    about = "Bounding volume hierarchies: build, measure, verify."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Build every top-down strategy and every bounding volume on the built-in
    /// scene (two overlapping rocks, 81 920 triangles each), time them, and check
    /// every collision query against brute force.
    Tour {
        /// Print the report as JSON instead of tables.
        #[arg(long)]
        json: bool,
        /// Icosphere subdivisions per rock (6 = 81 920 triangles; smaller is faster).
        #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u32).range(1..=7))]
        subdivisions: u32,
        /// Timed runs per measurement; the median is reported.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=50))]
        runs: u64,
    },
    /// Collide two objects and report the cost-function counters (Nv, Np, Nu),
    /// candidate and exactly intersecting triangle pairs, and the query time.
    ///
    /// Without mesh files: the built-in rock against a moved copy of the same
    /// tree (B is queried in A's frame through a rigid motion, not rebuilt).
    Collide {
        /// Mesh file of object A (.obj).
        #[arg(requires = "b")]
        a: Option<PathBuf>,
        /// Mesh file of object B (.obj), in the same frame as A.
        b: Option<PathBuf>,
        /// Descent rule (stack and recursive traversals): which tree to open
        /// when two internal nodes overlap.
        #[arg(long, default_value = "larger", value_parser = PossibleValuesParser::new(Descent::ALL.map(Descent::name)))]
        descent: String,
        /// Traversal: recursive (the lectures' code), stack (explicit fixed
        /// stack), simultaneous (both trees in lock step), leaf-directed (A to
        /// its leaves, then one descent of B per leaf).
        #[arg(long, default_value = "stack", value_parser = PossibleValuesParser::new(TRAVERSALS))]
        traversal: String,
        /// What to return: every pair, the first pair (early out), or the count.
        #[arg(long, value_enum, default_value_t = ModeArg::All)]
        mode: ModeArg,
        /// Bounding volume of the trees.
        #[arg(long, default_value = "aabb", value_parser = PossibleValuesParser::new(VOLUMES))]
        bv: String,
        /// Top-down builder preset.
        #[arg(long, default_value = "sah", value_parser = PossibleValuesParser::new(PRESETS.map(|p| p.name)))]
        builder: String,
        /// Icosphere subdivisions of the built-in rock (6 = 81 920 triangles).
        #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u32).range(1..=7))]
        subdivisions: u32,
        /// Timed runs; the median is reported.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=100))]
        runs: u64,
        /// Also compute the contacts by brute force and compare.
        #[arg(long)]
        verify: bool,
        /// Print the report as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Measure every tree representation (canonical, implicit array,
    /// preorder with 32- and 16-bit links, tri-node, 4-wide, quantized 4-wide)
    /// on the built-in rock pair: bytes per triangle, conversion time, pair and
    /// ray query time, and whether the answers equal the canonical tree's.
    Layouts {
        /// Icosphere subdivisions per rock (6 = 81 920 triangles, 8 = 1 310 720).
        #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u32).range(1..=9))]
        subdivisions: u32,
        /// Rays cast at rock A.
        #[arg(long, default_value_t = 10_000)]
        rays: usize,
        /// Timed runs per measurement; the median (or minimum for conversions) is reported.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=50))]
        runs: u64,
        /// Print the rows as JSON.
        #[arg(long)]
        json: bool,
    },
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum ModeArg {
    All,
    First,
    Count,
}

fn print_json<T: serde::Serialize>(value: &T) -> bool {
    match serde_json::to_string_pretty(value) {
        Ok(s) => {
            println!("{s}");
            true
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Layouts {
            subdivisions,
            rays,
            runs,
            json,
        } => {
            eprintln!("building the rock pair ({subdivisions} subdivisions) and every layout...");
            let (a, b) = bvhkit_std::scene::rock_pair(subdivisions);
            let rows = match bvhkit_std::layouts::measure(
                &a,
                &b,
                &bvhkit::TopDown::sah(),
                rays,
                runs as usize,
            ) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            };
            if json {
                if !print_json(&rows) {
                    return ExitCode::FAILURE;
                }
            } else {
                println!(
                    "scene: two rocks of {} triangles, sah builder, AABB, {} rays",
                    a.len(),
                    rays
                );
                print!("{}", bvhkit_std::layouts::render(&rows));
            }
            if rows.iter().all(|r| r.same_answers) {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Command::Tour {
            json,
            subdivisions,
            runs,
        } => {
            let opts = TourOptions {
                subdivisions,
                runs: runs as usize,
            };
            let report = tour::run(opts, |what| {
                eprint!("\rmeasuring {what:<24}");
                let _ = std::io::stderr().flush();
            });
            eprint!("\r{:<40}\r", "");
            let report = match report {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            };
            if json {
                if !print_json(&report) {
                    return ExitCode::FAILURE;
                }
            } else {
                print!("{}", tour::render(&report));
            }
            if report.verified == report.queries {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Command::Collide {
            a,
            b,
            descent,
            traversal,
            mode,
            bv,
            builder,
            subdivisions,
            runs,
            verify,
            json,
        } => {
            let input = match (a, b) {
                (Some(a), Some(b)) => {
                    let load = |p: &PathBuf| bvhkit_std::mesh::load(p);
                    match (load(&a), load(&b)) {
                        (Ok(ta), Ok(tb)) => Input::Meshes {
                            name: format!("{} and {}", a.display(), b.display()),
                            a: ta,
                            b: tb,
                        },
                        (Err(e), _) | (_, Err(e)) => {
                            eprintln!("error: {e}");
                            return ExitCode::FAILURE;
                        }
                    }
                }
                _ => Input::Default { subdivisions },
            };
            let opts = CollideOptions {
                volume: bv,
                builder,
                traversal,
                descent: Descent::from_name(&descent).unwrap_or_default(),
                mode: match mode {
                    ModeArg::All => Mode::All,
                    ModeArg::First => Mode::First,
                    ModeArg::Count => Mode::Count,
                },
                runs: runs as usize,
                verify,
            };
            let report = match collide::run(&input, &opts) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            };
            if json {
                if !print_json(&report) {
                    return ExitCode::FAILURE;
                }
            } else {
                print!("{}", collide::render(&report));
            }
            if report.verified == Some(false) {
                ExitCode::FAILURE
            } else {
                ExitCode::SUCCESS
            }
        }
    }
}
