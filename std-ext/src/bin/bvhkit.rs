//! The `bvhkit` command-line tool.

use bvhkit_std::tour::{self, TourOptions};
use clap::{Parser, Subcommand};
use std::io::Write;
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
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
                match serde_json::to_string_pretty(&report) {
                    Ok(s) => println!("{s}"),
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::FAILURE;
                    }
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
    }
}
