//! `--builder` accepts every builder of the library (top-down presets,
//! bottom-up, insertion) in `stats` and `collide`, and `--help` lists them.

use std::process::Command;

fn run(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args(args)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.success(), text)
}

#[test]
fn every_builder_is_offered_and_works() {
    // A small mesh: the exhaustive O(n^3) builder must finish quickly too.
    let dir = std::env::temp_dir().join(format!("bvhkit-cli-builders-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("rock.off");
    let tris = bvhkit_std::scene::rock(1, 2);
    let mut off = format!("OFF\n{} {} 0\n", 3 * tris.len(), tris.len());
    for t in &tris {
        for v in t.v {
            off += &format!("{} {} {}\n", v.x, v.y, v.z);
        }
    }
    for i in 0..tris.len() {
        off += &format!("3 {} {} {}\n", 3 * i, 3 * i + 1, 3 * i + 2);
    }
    std::fs::write(&mesh, off).unwrap();
    let mesh = mesh.to_str().unwrap();

    let (ok, help) = run(&["stats", "--help"]);
    assert!(ok);
    let names = bvhkit_std::builders::names();
    assert!(names.len() >= 24, "{names:?}");
    for name in names {
        assert!(help.contains(name), "--help does not list {name}");
        let (ok, text) = run(&["stats", mesh, "--builder", name, "--runs", "1"]);
        assert!(ok, "stats --builder {name}: {text}");
        assert!(text.contains(&format!("tree: {name} builder")), "{text}");
        let (ok, text) = run(&[
            "collide",
            mesh,
            mesh,
            "--builder",
            name,
            "--runs",
            "1",
            "--verify",
        ]);
        assert!(ok, "collide --builder {name}: {text}");
        assert!(text.contains("match"), "collide --builder {name}: {text}");
    }
    let (ok, text) = run(&["stats", mesh, "--builder", "ploc-r16", "--leaf-size", "2"]);
    assert!(
        !ok && text.contains("--leaf-size applies to the top-down builders"),
        "{text}"
    );
}
