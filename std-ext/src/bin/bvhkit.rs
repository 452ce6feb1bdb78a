//! The `bvhkit` command-line tool.

use bvhkit::Descent;
use bvhkit_std::collide::{self, CollideOptions, Input, Mode, TRAVERSALS, VOLUMES};
use bvhkit_std::tour::{self, TourOptions};
use clap::builder::PossibleValuesParser;
use clap::{Parser, Subcommand, ValueEnum};
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
        /// Mesh file of object A (.obj, .stl, .ply or .off).
        a: Option<PathBuf>,
        /// Mesh file of object B, in A's frame (default: a copy of A; place it
        /// with --scale-b, --rotate-b and --translate-b to make it overlap).
        /// On the built-in scene, --rotate-b and --translate-b move B further
        /// (after its default motion); --scale-b needs mesh files.
        b: Option<PathBuf>,
        /// Scale B about the origin (before rotating).
        #[arg(long, default_value_t = 1.0)]
        scale_b: f32,
        /// Rotate B by these angles in degrees about x, y and z, e.g. 0,30,0.
        #[arg(long, value_parser = parse_vec3, default_value = "0,0,0")]
        rotate_b: Vec3Arg,
        /// Translate B, e.g. 0.1,0,0 (after rotating).
        #[arg(long, value_parser = parse_vec3, default_value = "0,0,0")]
        translate_b: Vec3Arg,
        /// Descent rule (stack and recursive traversals): which tree to open
        /// when two internal nodes overlap.
        #[arg(long, default_value = "simultaneous", value_parser = PossibleValuesParser::new(Descent::ALL.map(Descent::name)))]
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
        /// Builder: a top-down preset, a bottom-up builder (ploc-r16, ploc-r4,
        /// ploc-r1, bottom-up-exhaustive) or an insertion builder (insert-*).
        #[arg(long, default_value = "sah", value_parser = PossibleValuesParser::new(bvhkit_std::builders::names()))]
        builder: String,
        /// Icosphere subdivisions of the built-in rock (6 = 81 920 triangles).
        #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u32).range(1..=7))]
        subdivisions: u32,
        /// Timed runs; the median is reported.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=100))]
        runs: u64,
        /// Also compute the contacts by brute force and compare (with
        /// --distance, also the distance, over every triangle pair: refused
        /// above 30 million pairs).
        #[arg(long)]
        verify: bool,
        /// Also measure the distance between A and B: the closest pair of
        /// triangles, their closest points and the query time (0 when they
        /// touch). On the built-in scene, B's triangles are moved and a tree
        /// is built over them for this query.
        #[arg(long, conflicts_with = "self_collide")]
        distance: bool,
        /// Self-collision: A's tree against itself, each triangle pair once,
        /// triangles that share a vertex skipped (takes one mesh; --verify
        /// compares with a sort-and-sweep).
        #[arg(long = "self", conflicts_with_all = ["b", "mode"])]
        self_collide: bool,
        /// Print the report as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Build one tree over a mesh and report its statistics: node and leaf
    /// counts, depth, balance, SAH cost, volume and area sums, sibling overlap,
    /// build time, and the bytes of every tree representation.
    Stats {
        /// Mesh file (.obj, .stl, .ply or .off); default: the built-in rock.
        mesh: Option<PathBuf>,
        /// Builder: a top-down preset, a bottom-up builder (ploc-r16, ploc-r4,
        /// ploc-r1, bottom-up-exhaustive) or an insertion builder (insert-*).
        #[arg(long, default_value = "sah", value_parser = PossibleValuesParser::new(bvhkit_std::builders::names()))]
        builder: String,
        /// Bounding volume of the tree.
        #[arg(long, default_value = "aabb", value_parser = PossibleValuesParser::new(VOLUMES))]
        bv: String,
        /// Most triangles per leaf (default: the preset's).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        leaf_size: Option<u32>,
        /// Timed builds; the median is reported.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=50))]
        runs: u64,
        /// Print the report as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Calibrate the cost function T = Nv*Cv + Nu*Cu + Np*Cp + Ne*Ce + Co from
    /// measured queries: time every traversal on built-in training scenes
    /// (round-robin, median of the rounds), fit the unit costs, then predict
    /// scenes the fit never saw (the default rock pair and the given meshes)
    /// and report how close each prediction is.
    CostModel {
        /// Mesh files to hold out (.obj, .stl, .ply or .off), each against a
        /// moved copy of itself.
        meshes: Vec<PathBuf>,
        /// Rounds of timing; each query's median is used.
        #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u64).range(1..=101))]
        rounds: u64,
        /// Small training scenes and a small held-out rock (seconds, not minutes).
        #[arg(long)]
        quick: bool,
        /// Print every query (counts, measured and predicted time) as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Run time against error: fit every volume type (time against
    /// looseness), build with every builder (time against SAH cost and query
    /// time, Pareto front marked) and lay the tree out in every
    /// representation (memory against extra volume tests), and measure every
    /// combination per scene and workload to see how far the advisor's pick
    /// is from the fastest. Writes report.md, report.json and SVG plots.
    Bench {
        /// Output folder.
        #[arg(long, default_value = "target/bvhkit-report")]
        out: PathBuf,
        /// Icosphere subdivisions per rock (5 = 20 480 triangles).
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=7))]
        subdivisions: u32,
        /// Timed runs per measurement; the median is reported.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=50))]
        runs: u64,
        /// Also print the report as JSON.
        #[arg(long)]
        json: bool,
        /// A real mesh to add (OBJ, STL, PLY or OFF; repeat for several):
        /// its volume fits and a builder table against a shifted copy of
        /// itself. `scripts/fetch-meshes` fetches some into data/meshes.
        #[arg(long)]
        mesh: Vec<PathBuf>,
        /// Only fit the volumes (seconds instead of minutes) and print the
        /// fit table; no files are written.
        #[arg(long)]
        fits_only: bool,
        /// Only build a tree of every volume type and run the pair query on
        /// it (build time, SAH, Nv, Np, query time); prints that table, no
        /// files are written.
        #[arg(long, conflicts_with = "fits_only")]
        volumes_only: bool,
    },
    /// Advise a builder, bounding volume, tree representation and traversal
    /// for a scene and workload, and say why. The advice comes from cheap
    /// scene statistics (primitive count, how evenly the primitives fill
    /// space, size spread, sliver ratio, the objects' relative size); with
    /// --measure, every combination is also measured on the scene (answers
    /// checked against brute force) and the advice is compared with the
    /// fastest.
    Advise {
        /// Mesh file (.obj, .stl, .ply or .off); object B is a turned and
        /// shifted copy. Default: the built-in rock pair.
        mesh: Option<PathBuf>,
        /// What the scene is queried for.
        #[arg(long, value_enum, default_value_t = QueryArg::Pairs)]
        query: QueryArg,
        /// How the scene moves: static (build once), rigid (B moves as a
        /// rigid body; build once, query through its pose), deforming
        /// (rebuild every frame).
        #[arg(long, value_enum, default_value_t = MotionArg::Static)]
        motion: MotionArg,
        /// Frames: queries per build (static, rigid) or rebuilds (deforming).
        #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
        frames: u64,
        /// Icosphere subdivisions of the built-in rocks (5 = 20 480 triangles).
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=7))]
        subdivisions: u32,
        /// Also measure every combination on this scene and compare.
        #[arg(long)]
        measure: bool,
        /// Rays per frame (rays workloads, with --measure).
        #[arg(long, default_value_t = 2_000)]
        rays: usize,
        /// Timed runs per measurement; the median is kept.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=50))]
        runs: u64,
        /// Print the advice (and measurements) as JSON.
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
    /// Build a mesh's tree (the default builder) and bake it into a file a
    /// firmware can `include_bytes!` and open in place with
    /// `Bvh::from_baked` (see `bvhkit::baked` for the format). The file is
    /// opened and validated against the mesh again before this exits 0.
    Bake {
        /// Mesh file (.obj, .stl, .ply or .off); default: the built-in rock.
        mesh: Option<PathBuf>,
        /// The file to write.
        #[arg(short, long)]
        out: PathBuf,
        /// Also store each triangle's box in leaf order (24 bytes a
        /// triangle): pair queries then never read a triangle to test it.
        #[arg(long)]
        leaf_bounds: bool,
        /// Bake the 4-wide layout (kind 2: 128-byte records, 64-byte
        /// aligned; open it with `Wide::from_baked`) instead of the binary
        /// tree.
        #[arg(long, conflicts_with = "quantized")]
        wide: bool,
        /// Bake the quantized 4-wide layout (kind 3: 64-byte records; open
        /// it with `QuantizedWide::from_baked`).
        #[arg(long)]
        quantized: bool,
    },
    /// Draw the book's figures (SVG, computed by the library itself) into
    /// the book's figures folder, or check the committed ones against what
    /// the code draws now.
    Figures {
        /// The book's `src` folder (figures go to its `figures/`; plots of
        /// recorded runs read its `measured/`).
        #[arg(default_value = "book/src")]
        book_src: PathBuf,
        /// Compare instead of writing: list every figure that differs, is
        /// missing or is drawn by nothing, and exit 1 if any.
        #[arg(long)]
        check: bool,
    },
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum QueryArg {
    Pairs,
    Rays,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum MotionArg {
    Static,
    Rigid,
    Deforming,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum ModeArg {
    All,
    First,
    Count,
}

/// A 3-vector given on the command line as `x,y,z`.
#[derive(Clone, Copy, Debug)]
struct Vec3Arg(bvhkit::glam::Vec3);

fn parse_vec3(s: &str) -> Result<Vec3Arg, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y, z] = parts[..] else {
        return Err(format!("'{s}' is not x,y,z"));
    };
    let num = |t: &str| {
        t.parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or(format!("'{t}' is not a finite number"))
    };
    Ok(Vec3Arg(bvhkit::glam::Vec3::new(num(x)?, num(y)?, num(z)?)))
}

/// Prints `report` as JSON or as `render` makes it; false if JSON failed.
fn show<T: serde::Serialize>(report: &T, json: bool, render: impl Fn(&T) -> String) -> bool {
    if json {
        print_json(report)
    } else {
        print!("{}", render(report));
        true
    }
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
        Command::Bake {
            mesh,
            out,
            leaf_bounds,
            wide,
            quantized,
        } => {
            let tris = match &mesh {
                Some(p) => match bvhkit_std::mesh::load(p) {
                    Ok(t) => t,
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::FAILURE;
                    }
                },
                None => bvhkit_std::scene::rock(6, 1),
            };
            let layout = match (wide, quantized) {
                (_, true) => Some(true),
                (true, false) => Some(false),
                _ => None,
            };
            match bake(&tris, &out, leaf_bounds, layout) {
                Ok(text) => {
                    print!("{text}");
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Command::Figures { book_src, check } => {
            use bvhkit_std::figures;
            let dir = book_src.join("figures");
            let result = if check {
                figures::check(&book_src, &dir).map(|problems| {
                    for p in &problems {
                        eprintln!("{p}");
                    }
                    if problems.is_empty() {
                        println!("every figure in {} matches the code", dir.display());
                    }
                    problems.is_empty()
                })
            } else {
                figures::write_all(&book_src, &dir).map(|written| {
                    println!("{} figures written to {}", written.len(), dir.display());
                    true
                })
            };
            match result {
                Ok(true) => ExitCode::SUCCESS,
                Ok(false) => ExitCode::FAILURE,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Command::Advise {
            mesh,
            query,
            motion,
            frames,
            subdivisions,
            measure,
            rays,
            runs,
            json,
        } => {
            use bvhkit_std::advisor::{self, Case, Motion, QueryKind, Workload};
            let workload = Workload {
                query: match query {
                    QueryArg::Pairs => QueryKind::Pairs,
                    QueryArg::Rays => QueryKind::Rays,
                },
                motion: match motion {
                    MotionArg::Static => Motion::Static,
                    MotionArg::Rigid => Motion::Rigid,
                    MotionArg::Deforming => Motion::Deforming,
                },
                frames: frames as usize,
            };
            let bar = spinner("loading");
            let case = match &mesh {
                Some(p) => bvhkit_std::mesh::load(p)
                    .map_err(|e| e.to_string())
                    .and_then(|t| {
                        Case::from_mesh(&p.display().to_string(), &t).map_err(|e| e.to_string())
                    }),
                None => Case::generated(subdivisions)
                    .map_err(|e| e.to_string())
                    .map(|mut cases| cases.swap_remove(0)),
            };
            let case = match case {
                Ok(c) => c,
                Err(e) => return fail(e),
            };
            let report =
                advisor::advise_case(&case, &workload, measure, rays, runs as usize, |what| {
                    bar.set_message(format!("measuring {what}"))
                });
            bar.finish_and_clear();
            let report = match report {
                Ok(r) => r,
                Err(e) => return fail(e),
            };
            if json {
                if !print_json(&report) {
                    return ExitCode::FAILURE;
                }
            } else {
                print!("{}", advisor::render_case(&report));
            }
            if report.measured.iter().all(|r| r.all_verified) {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Command::Stats {
            mesh,
            builder,
            bv,
            leaf_size,
            runs,
            json,
        } => {
            let bar = spinner("loading and building");
            let (name, tris) = match &mesh {
                Some(p) => match bvhkit_std::mesh::load(p) {
                    Ok(t) => (p.display().to_string(), t),
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::FAILURE;
                    }
                },
                None => (
                    "built-in rock (6 subdivisions)".to_string(),
                    bvhkit_std::scene::rock(6, 1),
                ),
            };
            let opts = bvhkit_std::stats::StatsOptions {
                builder,
                volume: bv,
                leaf_size,
                runs: runs as usize,
            };
            let stats = bvhkit_std::stats::run(&name, &tris, &opts);
            bar.finish_and_clear();
            match stats {
                Ok(r) if json => {
                    if !print_json(&r) {
                        return ExitCode::FAILURE;
                    }
                }
                Ok(r) => print!("{}", bvhkit_std::stats::render(&r)),
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            }
            ExitCode::SUCCESS
        }
        Command::Bench {
            out,
            subdivisions,
            runs,
            json,
            mesh,
            fits_only,
            volumes_only,
        } => {
            let bar = spinner("loading meshes");
            let mut meshes = Vec::new();
            for p in &mesh {
                match bvhkit_std::mesh::load(p) {
                    Ok(t) => {
                        let name = p.file_name().map_or_else(
                            || p.display().to_string(),
                            |f| f.to_string_lossy().into_owned(),
                        );
                        meshes.push((name, t));
                    }
                    Err(e) => {
                        drop(bar);
                        eprintln!("error: {e}");
                        return ExitCode::FAILURE;
                    }
                }
            }
            if fits_only {
                let fits =
                    bvhkit_std::report::run_fits(subdivisions, runs as usize, &meshes, |what| {
                        bar.set_message(what.to_string())
                    });
                bar.finish_and_clear();
                if json {
                    if !print_json(&fits) {
                        return ExitCode::FAILURE;
                    }
                } else {
                    print!("{}", bvhkit_std::report::render_fits(&fits));
                }
                return ExitCode::SUCCESS;
            }
            if volumes_only {
                let rows =
                    bvhkit_std::report::run_volumes(subdivisions, runs as usize, &meshes, |what| {
                        bar.set_message(what.to_string())
                    });
                bar.finish_and_clear();
                let rows = match rows {
                    Ok(rows) => rows,
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
                    print!("{}", bvhkit_std::volumes::render(&rows));
                }
                return ExitCode::SUCCESS;
            }
            let report =
                bvhkit_std::report::run_with_meshes(subdivisions, runs as usize, &meshes, |what| {
                    bar.set_message(what.to_string())
                });
            bar.finish_and_clear();
            let report = match report {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            };
            match bvhkit_std::report::write(&report, &out) {
                Ok(files) => {
                    for f in files {
                        eprintln!("wrote {}", f.display());
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            }
            if json && !print_json(&report) {
                return ExitCode::FAILURE;
            }
            if report.builders.iter().all(|b| b.verified)
                && report.layouts.iter().all(|l| l.same_answers)
                && report.advisor.iter().all(|a| a.all_verified)
            {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Command::Layouts {
            subdivisions,
            rays,
            runs,
            json,
        } => {
            let bar = spinner(&format!(
                "building the rock pair ({subdivisions} subdivisions) and measuring every layout"
            ));
            let (a, b) = bvhkit_std::scene::rock_pair(subdivisions);
            let rows =
                bvhkit_std::layouts::measure(&a, &b, &bvhkit::TopDown::sah(), rays, runs as usize);
            bar.finish_and_clear();
            let rows = match rows {
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
        Command::CostModel {
            meshes,
            rounds,
            quick,
            json,
        } => {
            use bvhkit_std::cost_fit::{self, Scene};
            let (rock, label) = if quick {
                (bvhkit_std::scene::rock(4, 1), "")
            } else {
                (bvhkit_std::scene::default_pair().0, " (default)")
            };
            let name = format!("rock {}{label}", rock.len());
            let mut held_out = vec![Scene::new(&name, rock, cost_fit::check_motions())];
            for p in &meshes {
                match bvhkit_std::mesh::load(p) {
                    // An empty scene is valid, but its queries are only fixed
                    // cost: nothing for the model to predict.
                    Ok(m) if m.is_empty() => {
                        eprintln!("note: {} has no triangles: nothing to predict", p.display())
                    }
                    Ok(m) => {
                        let name = p.file_stem().map_or_else(
                            || p.display().to_string(),
                            |s| s.to_string_lossy().into_owned(),
                        );
                        held_out.push(Scene::new(&name, m, cost_fit::check_motions()));
                    }
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::FAILURE;
                    }
                }
            }
            let training = cost_fit::training_scenes(quick);
            let bar = spinner("measuring");
            let report = cost_fit::run(&training, &held_out, rounds as usize, |what| {
                bar.set_message(format!("cost model: {what}"))
            });
            bar.finish_and_clear();
            match report {
                Ok(r) if show(&r, json, cost_fit::render) => ExitCode::SUCCESS,
                Ok(_) => ExitCode::FAILURE,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
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
            let bar = spinner("measuring");
            let report = tour::run(opts, |what| bar.set_message(format!("measuring {what}")));
            bar.finish_and_clear();
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
            scale_b,
            rotate_b,
            translate_b,
            descent,
            traversal,
            mode,
            bv,
            builder,
            subdivisions,
            runs,
            verify,
            distance,
            self_collide,
            json,
        } => {
            let bar = spinner("loading, building and colliding");
            if self_collide {
                let (name, mesh) = match &a {
                    Some(a) => match bvhkit_std::mesh::load_indexed(a) {
                        Ok(m) => (a.display().to_string(), m),
                        Err(e) => {
                            bar.finish_and_clear();
                            eprintln!("error: {e}");
                            return ExitCode::FAILURE;
                        }
                    },
                    None => {
                        let triangles = bvhkit_std::scene::rock(subdivisions, 1);
                        let corners = bvhkit_std::mesh::weld(&triangles);
                        let mesh = bvhkit_std::mesh::IndexedMesh { triangles, corners };
                        (format!("rock ({subdivisions} subdivisions)"), mesh)
                    }
                };
                let opts = CollideOptions {
                    volume: bv,
                    builder,
                    traversal,
                    descent: Descent::from_name(&descent).unwrap_or_default(),
                    runs: runs as usize,
                    verify,
                    ..CollideOptions::default()
                };
                let report = collide::run_self(&name, &mesh.triangles, &mesh.corners, &opts);
                bar.finish_and_clear();
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
                    print!("{}", collide::render_self(&report));
                }
                return if report.verified == Some(false) {
                    ExitCode::FAILURE
                } else {
                    ExitCode::SUCCESS
                };
            }
            let placement = bvhkit_std::mesh::Placement {
                scale: scale_b,
                rotate_deg: rotate_b.0,
                translate: translate_b.0,
            };
            let input = match a {
                Some(a) => {
                    let b_path = b.clone().unwrap_or_else(|| a.clone());
                    let load = |p: &PathBuf| bvhkit_std::mesh::load(p);
                    let loaded = load(&a).and_then(|ta| Ok((ta, load(&b_path)?)));
                    match loaded {
                        Ok((ta, tb)) => match placement.apply(&tb) {
                            Ok(tb) => Input::Meshes {
                                name: format!("{} and {} (placed)", a.display(), b_path.display()),
                                a: ta,
                                b: tb,
                            },
                            Err(e) => {
                                eprintln!("error: placing B: {e}");
                                return ExitCode::FAILURE;
                            }
                        },
                        Err(e) => {
                            eprintln!("error: {e}");
                            return ExitCode::FAILURE;
                        }
                    }
                }
                // The built-in scene: B's tree is moved after the default
                // motion, not rebuilt, so only a rigid placement applies.
                None => match placement.rigid() {
                    Ok(placement) => Input::Default {
                        subdivisions,
                        placement,
                    },
                    Err(e) => {
                        eprintln!("error: placing B: {e}");
                        return ExitCode::FAILURE;
                    }
                },
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
                distance,
            };
            let report = collide::run(&input, &opts);
            bar.finish_and_clear();
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
                print!("{}", collide::render(&report));
            }
            let mut ok = report.verified != Some(false);
            if let Some(d) = report.closest.as_ref() {
                if d.distance_verified == Some(false) {
                    eprintln!(
                        "error: the distance query found {:?}, brute force {:?}",
                        d.distance, d.reference_distance
                    );
                    ok = false;
                }
            }
            if ok {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// Prints the error and returns failure.
fn fail(e: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::FAILURE
}

/// A spinner on stderr for anything that may take more than a second; it
/// draws only when stderr is a terminal, so logs and pipes stay clean.
fn spinner(message: &str) -> indicatif::ProgressBar {
    // Cleared when dropped too, so an early error return leaves no stale line.
    let bar =
        indicatif::ProgressBar::new_spinner().with_finish(indicatif::ProgressFinish::AndClear);
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar.set_message(message.to_string());
    bar
}

/// `bvhkit bake --wide` / `--quantized`: collapses `tree` to 4-wide
/// records (quantized or not), bakes and writes them, reads the file back
/// into 64-byte aligned memory, opens it as a device would and validates it
/// against the triangles; returns the report.
fn bake_wide(
    tris: &[bvhkit::Triangle],
    tree: &bvhkit::Bvh<'_, bvhkit::Aabb>,
    out: &std::path::Path,
    quantized: bool,
) -> Result<String, String> {
    use bvhkit::layout::{QuantNode, QuantizedWide, Wide, WideNode};
    use bvhkit::Hierarchy;
    let err = |e: bvhkit::Error| format!("{}: {e}", out.display());
    let bytes = if quantized {
        let mut records = vec![QuantNode::ZERO; QuantizedWide::records_needed(tree).map_err(err)?];
        let q = QuantizedWide::from_bvh(tree, &mut records).map_err(err)?;
        let mut bytes = vec![0u8; q.baked_len()];
        q.bake(&mut bytes).map_err(err)?;
        bytes
    } else {
        let mut records = vec![WideNode::ZERO; Wide::records_needed(tree).map_err(err)?];
        let wide = Wide::from_bvh(tree, &mut records).map_err(err)?;
        let mut bytes = vec![0u8; wide.baked_len()];
        wide.bake(&mut bytes).map_err(err)?;
        bytes
    };
    std::fs::write(out, &bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    let back = std::fs::read(out).map_err(|e| format!("{}: {e}", out.display()))?;
    // The records need a 64-byte boundary, which a `Vec<u8>` does not
    // promise: copy the bytes to one inside a slightly larger buffer.
    let mut store = vec![0u8; back.len() + 64];
    let at = store.as_ptr().align_offset(64).min(64);
    store[at..at + back.len()].copy_from_slice(&back);
    let aligned = &store[at..at + back.len()];
    let (records, nodes, depth) = if quantized {
        let mut seen = vec![0u32; QuantizedWide::baked_seen_words(aligned).map_err(err)?];
        let opened = QuantizedWide::from_baked(aligned, &mut seen).map_err(err)?;
        opened.validate(tris).map_err(err)?;
        (opened.records().len(), opened.node_count(), opened.depth())
    } else {
        let mut seen = vec![0u32; Wide::baked_seen_words(aligned).map_err(err)?];
        let opened = Wide::from_baked(aligned, &mut seen).map_err(err)?;
        opened.validate(tris).map_err(err)?;
        (opened.records().len(), opened.node_count(), opened.depth())
    };
    Ok(format!(
        "triangles {}\nrecords {records}\nnodes {nodes}\ndepth {depth}\nbytes {}\nbytes per triangle {:.1}\nwritten {} (opened and validated again)\n",
        tris.len(),
        back.len(),
        back.len() as f64 / tris.len().max(1) as f64,
        out.display()
    ))
}

/// `bvhkit bake`: builds, bakes, writes, reads the file back and opens it
/// as a device would; returns the report.
fn bake(
    tris: &[bvhkit::Triangle],
    out: &std::path::Path,
    kept: bool,
    wide: Option<bool>,
) -> Result<String, String> {
    use bvhkit::{Aabb, Bvh, TopDown};
    let owned = bvhkit_std::OwnedBvh::<Aabb>::build(&TopDown::default(), tris)
        .map_err(|e| e.to_string())?;
    let tree = if kept {
        owned.view()
    } else {
        owned.plain_view()
    };
    // `Some(quantized)`: one of the 4-wide layouts.
    if let Some(quantized) = wide {
        return bake_wide(tris, &tree, out, quantized);
    }
    let mut bytes = vec![0u8; tree.baked_len()];
    tree.bake(&mut bytes).map_err(|e| e.to_string())?;
    std::fs::write(out, &bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    let back = std::fs::read(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let words = Bvh::baked_seen_words(&back).map_err(|e| e.to_string())?;
    let mut seen = vec![0u32; words];
    let opened =
        Bvh::from_baked(&back, &mut seen).map_err(|e| format!("{}: {e}", out.display()))?;
    opened
        .validate(tris, &mut seen)
        .map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(format!(
        "triangles {}\nnodes {}\ndepth {}\nbytes {}\nbytes per triangle {:.1}\nwritten {} (opened and validated again)\n",
        tris.len(),
        opened.node_count(),
        opened.depth(),
        back.len(),
        back.len() as f64 / tris.len().max(1) as f64,
        out.display()
    ))
}
