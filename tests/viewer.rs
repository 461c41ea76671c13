//! The live viewer, tested for real: under a virtual X server (Xvfb), keys and
//! mouse events from xdotool, screenshots of the window by ImageMagick's `import`.
//! The picture must equal `lumiere render` of the same view, change when the
//! method changes, when the light moves and when the camera turns, show two exact
//! methods as identical in the split screen's difference, and the viewer must quit
//! on its key with exit status 0. The project's script installs the X tools when
//! missing (`.ci/run` runs it too).

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The X tools, installed by the project's script when missing (once a test binary:
/// its tests ask from several threads).
fn installed() {
    static INSTALLED: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    INSTALLED.get_or_init(install_when_missing);
}

fn install_when_missing() {
    let all = ["Xvfb", "xdotool", "import"].iter().all(|tool| {
        Command::new("sh")
            .args(["-c", &format!("command -v {tool}")])
            .stdout(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    });
    if !all {
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/install-display.sh");
        let status = Command::new(&script)
            .status()
            .expect("the install script runs");
        assert!(status.success(), "{} failed", script.display());
    }
}

/// A virtual X server on a display number nobody uses, stopped when dropped.
struct Display {
    server: Child,
    name: String,
}

impl Drop for Display {
    fn drop(&mut self) {
        let _ = self.server.kill();
        let _ = self.server.wait();
    }
}

impl Display {
    fn start() -> Display {
        installed();
        // Xvfb chooses a free display number and writes it on its standard output.
        // Without -noreset it resets whenever its last client leaves, and refuses
        // connections meanwhile: the viewer, starting while xdotool came and went,
        // now and then could not open the display.
        let mut server = Command::new("Xvfb")
            .args([
                "-noreset",
                "-displayfd",
                "1",
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts");
        let mut line = String::new();
        std::io::BufRead::read_line(
            &mut std::io::BufReader::new(server.stdout.take().unwrap()),
            &mut line,
        )
        .unwrap();
        let number: u32 = line.trim().parse().expect("Xvfb names its display");
        let name = format!(":{number}");
        Display { server, name }
    }

    fn command(&self, program: &str) -> Command {
        let mut command = Command::new(program);
        command
            .env("DISPLAY", &self.name)
            .env_remove("WAYLAND_DISPLAY");
        command
    }

    fn xdotool(&self, args: &[&str]) -> String {
        let out = self.command("xdotool").args(args).output().unwrap();
        assert!(
            out.status.success(),
            "xdotool {args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).trim().to_string()
    }

    /// The window's pixels (8-bit RGB), read from the X server.
    fn screenshot(&self, window: &str) -> Vec<u8> {
        let out = self
            .command("import")
            .args(["-window", window, "png:-"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "import: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        image::load_from_memory(&out.stdout)
            .unwrap()
            .to_rgb8()
            .into_raw()
    }

    /// The window's picture once it has changed from `before` and stopped
    /// changing.
    fn settled_after(&self, window: &str, before: &[u8]) -> Vec<u8> {
        let deadline = Instant::now() + Duration::from_secs(20);
        while self.screenshot(window) == before {
            assert!(Instant::now() < deadline, "the window never changed");
            std::thread::sleep(Duration::from_millis(50));
        }
        self.settled(window)
    }

    /// The window's picture once it has stopped changing (the viewer refines a
    /// moving view after it stops).
    fn settled(&self, window: &str) -> Vec<u8> {
        let mut last = self.screenshot(window);
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            std::thread::sleep(Duration::from_millis(400));
            let now = self.screenshot(window);
            if now == last {
                return now;
            }
            assert!(Instant::now() < deadline, "the window never settled");
            last = now;
        }
    }
}

const SIZE: &str = "160";

/// `lumiere render` of the point-lit box at the viewer's size, as 8-bit RGB.
fn rendered(dir: &Path, method: &str) -> Vec<u8> {
    render(dir, &["cornell-box-point", "--shadows", method])
}

fn render(dir: &Path, args: &[&str]) -> Vec<u8> {
    let out = dir.join("render.png");
    let status = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .arg("render")
        .args(args)
        .args(["--width", SIZE, "--height", SIZE, "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    image::open(&out).unwrap().to_rgb8().into_raw()
}

/// The viewer on `args`, its window found and focused.
fn open(display: &Display, args: &[&str], title: &str) -> (Child, String) {
    let viewer = display
        .command(env!("CARGO_BIN_EXE_lumiere"))
        .arg("view")
        .args(args)
        .args(["--width", SIZE, "--height", SIZE])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The window, once it is there (and never waiting on a viewer that has ended).
    let mut viewer = viewer;
    let deadline = Instant::now() + Duration::from_secs(30);
    let window = loop {
        let out = display
            .command("xdotool")
            .args(["search", "--name", title])
            .output()
            .unwrap();
        if let Some(id) = String::from_utf8_lossy(&out.stdout).lines().next() {
            break id.to_string();
        }
        if let Some(status) = viewer.try_wait().unwrap() {
            let out = viewer.wait_with_output().unwrap();
            panic!(
                "the viewer ended ({status}): {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        assert!(Instant::now() < deadline, "no window appeared");
        std::thread::sleep(Duration::from_millis(50));
    };
    display.xdotool(&["windowfocus", "--sync", &window]);
    // A key sent before the first frame is shown can be lost (the HUD key was,
    // now and then): the window is handed over once it shows a picture.
    while display.screenshot(&window).iter().all(|&c| c == 0) {
        assert!(Instant::now() < deadline, "no picture appeared");
        std::thread::sleep(Duration::from_millis(50));
    }
    (viewer, window)
}

/// Sends q and waits for the viewer to end with status 0.
fn quit(display: &Display, mut viewer: Child) {
    display.xdotool(&["key", "q"]);
    let deadline = Instant::now() + Duration::from_secs(20);
    let status = loop {
        if let Some(status) = viewer.try_wait().unwrap() {
            break status;
        }
        assert!(Instant::now() < deadline, "the viewer did not quit");
        std::thread::sleep(Duration::from_millis(50));
    };
    let out = viewer.wait_with_output().unwrap();
    assert!(status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Pixels (of 3 bytes) that differ.
fn differing(a: &[u8], b: &[u8]) -> usize {
    assert_eq!(a.len(), b.len());
    a.chunks(3).zip(b.chunks(3)).filter(|(p, q)| p != q).count()
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Xvfb, xdotool and ImageMagick (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_viewer_shows_what_render_makes_and_follows_keys_and_mouse() {
    let display = Display::start();
    let dir = tempfile::tempdir().unwrap();
    let (viewer, window) = open(
        &display,
        &["cornell-box-point", "--shadows", "scanline"],
        "lumiere: cornell-box-point",
    );
    // Each step presses its keys and waits for the picture to change, then to
    // settle: two equal screenshots alone could be a window not yet redrawn.
    let press = |keys: &[&str]| {
        let before = display.screenshot(&window);
        for k in keys {
            display.xdotool(&["key", k]);
        }
        display.settled_after(&window, &before)
    };

    // The overlay hidden, the picture is render's, byte for byte.
    let scanline = press(&["h"]);
    assert_eq!(scanline.len(), 160 * 160 * 3);
    assert_eq!(differing(&scanline, &rendered(dir.path(), "scanline")), 0);

    // Method 1 is no shadows: another picture, render's too.
    let none = press(&["1"]);
    assert!(differing(&none, &scanline) > 500);
    assert_eq!(differing(&none, &rendered(dir.path(), "none")), 0);

    // Back to scan-line shadows (method 3), then the split screen with the next
    // method, shadow polygons: exact both, so their difference is black.
    assert_eq!(press(&["3"]), scanline);
    let split = press(&["s"]);
    // Only the divider between the halves differs.
    assert_eq!(differing(&split, &scanline), 160);
    let difference = press(&["d"]);
    assert!(difference.iter().all(|&c| c == 0), "exact methods differ");
    assert_eq!(press(&["d", "s"]), scanline);

    // A buffer instead of the picture (the polygon ids first); a number key
    // brings the picture back.
    let buffer = press(&["b"]);
    assert!(differing(&buffer, &scanline) > 1000);
    assert_eq!(press(&["3"]), scanline);

    // The light moves left, and the shadows with it; moved back, the picture is
    // the first again (the light's shadows were made again, twice).
    let moved = press(&["Left", "Left", "Left"]);
    assert!(differing(&moved, &scanline) > 200);
    assert_eq!(press(&["Right", "Right", "Right"]), scanline);

    // A drag turns the camera.
    display.xdotool(&[
        "mousemove",
        "--window",
        &window,
        "40",
        "80",
        "mousedown",
        "1",
    ]);
    for x in [50, 60, 70, 80, 90, 100] {
        display.xdotool(&["mousemove", "--window", &window, &x.to_string(), "80"]);
    }
    display.xdotool(&["mouseup", "1"]);
    let turned = display.settled_after(&window, &scanline);
    assert!(differing(&turned, &scanline) > 1000);

    quit(&display, viewer);
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Xvfb, xdotool and ImageMagick (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn progressive_radiosity_shows_its_intermediate_states_and_ends_as_render_does() {
    let display = Display::start();
    let dir = tempfile::tempdir().unwrap();
    // Hemi-cubes of 256 (the entry's are 128) make the solve last longer (1.5 s
    // rather than 0.9 s alone), for screenshots to catch its states on a busy
    // machine.
    let scene = ["radiosity-shooting", "--set", "radiosity.resolution=256"];
    let (viewer, window) = open(&display, &scene, "lumiere: radiosity-shooting");
    display.xdotool(&["key", "h"]);
    // Shooting hands its state over as it goes (every 150 ms): the picture
    // changes several times, then stays. Every picture that differs from the one
    // before is kept; three seconds without a change is the end.
    let mut states = vec![display.screenshot(&window)];
    let mut changed = Instant::now();
    let deadline = Instant::now() + Duration::from_secs(60);
    while changed.elapsed() < Duration::from_secs(3) {
        assert!(Instant::now() < deadline, "the solve never ended");
        std::thread::sleep(Duration::from_millis(50));
        let now = display.screenshot(&window);
        if now != *states.last().unwrap() {
            states.push(now);
            changed = Instant::now();
        }
    }
    assert!(states.len() >= 4, "{} states seen", states.len());
    let expected = render(dir.path(), &scene);
    let mut last = states.pop().unwrap();
    // On a loaded machine the h pressed at the start is now and then lost (the
    // overlay, many lines on a small window, then darkens nearly all of it): it
    // is pressed again, once, and the picture must then be render's.
    if differing(&last, &expected) != 0 {
        display.xdotool(&["key", "h"]);
        last = display.settled_after(&window, &last);
    }
    assert_eq!(differing(&last, &expected), 0);
    quit(&display, viewer);
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Xvfb, xdotool and ImageMagick (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_texture_filter_key_forces_a_filter_on_every_texture() {
    let display = Display::start();
    let dir = tempfile::tempdir().unwrap();
    let (viewer, window) = open(&display, &["mip-mapping"], "lumiere: mip-mapping");
    let before = display.screenshot(&window);
    display.xdotool(&["key", "h"]);
    let scene = display.settled_after(&window, &before);
    assert_eq!(differing(&scene, &render(dir.path(), &["mip-mapping"])), 0);
    // The first filter is point sampling, on both planes.
    display.xdotool(&["key", "f"]);
    let nearest = display.settled_after(&window, &scene);
    assert!(differing(&nearest, &scene) > 500);
    let both = [
        "mip-mapping",
        "--set",
        "textures.point.filter=\"nearest\"",
        "--set",
        "textures.trilinear.filter=\"nearest\"",
    ];
    assert_eq!(differing(&nearest, &render(dir.path(), &both)), 0);
    quit(&display, viewer);
}

#[test]
fn without_a_display_the_viewer_says_so_in_one_line() {
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["view", "cornell-box-point"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("needs a display"), "{stderr}");
}

/// A DISPLAY where no X server answers: one line naming it, without the windowing
/// library's source file.
#[test]
fn a_display_without_a_server_is_named_in_one_line() {
    let free = (90..1000)
        .find(|n| !Path::new(&format!("/tmp/.X11-unix/X{n}")).exists())
        .unwrap();
    let display = format!(":{free}");
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["view", "cornell-box-point"])
        .env("DISPLAY", &display)
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: cannot open the display {display}: ")),
        "{stderr}"
    );
    assert!(
        !stderr.contains(".rs:") && !stderr.contains(".cargo"),
        "{stderr}"
    );
}
