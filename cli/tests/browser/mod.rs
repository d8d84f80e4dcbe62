//! Headless Chromium for the viewer's tests and benchmark: a fresh profile per run, no
//! network, standard output through a file; and reading the attributes of the page it
//! dumps. A file that takes it also takes `common` (the PATH lookup is there).

#![allow(dead_code)] // each test or bench file uses its own part
#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Window size of every page opened, CSS pixels (device scale 1).
pub const WINDOW: (u32, u32) = (1000, 650);

/// A fresh scratch directory for this process.
pub fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("viewer-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The browser, or `None` (with a note) when there is none outside CI.
pub fn browser() -> Option<PathBuf> {
    crate::common::on_path(
        &["chromium", "chromium-browser", "google-chrome"],
        "Chromium",
        "browser",
    )
}

/// Runs headless Chromium on `url` with `args` (a fresh profile, no network), one at a time
/// in this process, each for at most a minute; returns its standard output. The page's
/// viewport is [`WINDOW`] both for `--screenshot` and for `--dump-dom` (whose pages
/// Chromium gives a viewport shorter than the window: [`dump_dom_window`]).
pub fn chromium(exe: &Path, url: &str, args: &[String]) -> String {
    // one browser at a time: pages report their drawing time, which a second browser
    // competing for the two cores would double
    static ONE: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one = ONE.lock().unwrap_or_else(|e| e.into_inner());
    let window = if args.iter().any(|a| a == "--dump-dom") {
        dump_dom_window(exe)
    } else {
        WINDOW
    };
    launch(exe, url, args, window)
}

/// The window that gives a `--dump-dom` page the viewport [`WINDOW`]: headless Chromium
/// takes the height of its own bars from the window there (139 px in Chromium 148) but not
/// for `--screenshot`; measured once per process on a page that reports its viewport.
pub fn dump_dom_window(exe: &Path) -> (u32, u32) {
    static MEASURED: std::sync::OnceLock<(u32, u32)> = std::sync::OnceLock::new();
    *MEASURED.get_or_init(|| {
        let dir = tmp("viewport");
        let page = dir.join("viewport.html");
        std::fs::write(
            &page,
            "<html><body><script>document.body.setAttribute('data-viewport', \
             innerWidth + 'x' + innerHeight);</script></body></html>",
        )
        .unwrap();
        let dom = launch(exe, &url(&page, ""), &["--dump-dom".into()], WINDOW);
        let _ = std::fs::remove_dir_all(&dir);
        let seen = attributes(&dom, "body", "data-viewport");
        let (w, h) = attr(&seen, "data-viewport").split_once('x').unwrap();
        let (w, h): (u32, u32) = (w.parse().unwrap(), h.parse().unwrap());
        (
            WINDOW.0 + WINDOW.0.saturating_sub(w),
            WINDOW.1 + WINDOW.1.saturating_sub(h),
        )
    })
}

/// Runs headless Chromium on `url` with `args` in a window of `window` CSS pixels.
fn launch(exe: &Path, url: &str, args: &[String], window: (u32, u32)) -> String {
    let profile = tmp(&format!("profile-{}", rand_tag()));
    // standard output to a file: a pipe would fill up and stall the browser
    let dump = profile.with_extension("out");
    let mut child = Command::new(exe)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
        ])
        .arg(format!("--window-size={},{}", window.0, window.1))
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(url)
        .stdout(std::fs::File::create(&dump).unwrap())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("chromium did not finish within a minute on {url}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = std::fs::read(&dump).unwrap();
    let _ = std::fs::remove_dir_all(&profile);
    let _ = std::fs::remove_file(&dump);
    String::from_utf8_lossy(&out).into_owned()
}

/// A tag unique within this process.
pub fn rand_tag() -> String {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    N.fetch_add(1, Ordering::Relaxed).to_string()
}

/// The file URL of `page` with `hash`.
pub fn url(page: &Path, hash: &str) -> String {
    format!("file://{}#{hash}", page.canonicalize().unwrap().display())
}

/// The attributes of the first element opening with `<tag` whose attributes contain `having`.
pub fn attributes(dom: &str, tag: &str, having: &str) -> Vec<(String, String)> {
    let open = format!("<{tag} ");
    let start = dom
        .match_indices(&open)
        .map(|(i, _)| i)
        .find(|&i| dom[i..].split('>').next().unwrap().contains(having))
        .unwrap_or_else(|| panic!("no <{tag} {having}> in the page"));
    let text = &dom[start + open.len()..start + dom[start..].find('>').unwrap()];
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(eq) = rest.find("=\"") {
        let name = rest[..eq].trim().to_string();
        let after = &rest[eq + 2..];
        let close = after.find('"').unwrap();
        out.push((name, after[..close].replace("&amp;", "&")));
        rest = &after[close + 1..];
    }
    out
}

/// The value of attribute `name`.
pub fn attr<'a>(attrs: &'a [(String, String)], name: &str) -> &'a str {
    attrs
        .iter()
        .find(|a| a.0 == name)
        .map(|a| a.1.as_str())
        .unwrap_or_else(|| panic!("no {name} in {attrs:?}"))
}

/// Rows of `row` tiles joined by tight U-turns of alternating sense, `tiles` in all, as a
/// fold word (`S*k L L S*k R R ...`).
pub fn serpentine(tiles: usize, row: usize) -> String {
    let mut parts = Vec::new();
    let (mut letters, mut left) = (0, true);
    while letters + 1 < tiles {
        let straight = (row - 1).min(tiles - 1 - letters);
        parts.push(format!("S*{straight}"));
        letters += straight;
        for _ in 0..2 {
            if letters + 1 < tiles {
                parts.push(if left { "L" } else { "R" }.to_string());
                letters += 1;
            }
        }
        left = !left;
    }
    parts.join(" ")
}
