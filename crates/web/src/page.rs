//! What one page has open, and the calls its JavaScript makes on it.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use serde::Deserialize;
use serde_json::{Value, json};

use raystep_engine::input_file::{self, GivenFiles};
use raystep_engine::printable::printable_text;
use raystep_engine::render::render;
use raystep_engine::scene::{self, Scene, Settings, SpecularModel};
use raystep_engine::trace::NoRecorder;

use raystep_tools::diagram::svg::Caption;

use crate::options::{Options, catalogue};
use crate::page_size::check_page_size;
use crate::pixel_view::PixelView;
use crate::reply::Reply;
use crate::student_work::StudentWork;

/// The scene read, as it was named and at the size asked.
struct Loaded {
    path: PathBuf,
    size: Option<(u32, u32)>,
    scene: Scene,
}

/// One page's state: the files given, the scene, the toggles, the pixel
/// looked at and the student's work dropped on it.
#[derive(Default)]
pub struct Page {
    files: GivenFiles,
    loaded: Option<Loaded>,
    options: Options,
    pixel: Option<PixelView>,
    work: StudentWork,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Named {
    path: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LoadArgs {
    path: String,
    /// `--size`: the scene's own size when left out.
    size: Option<(u32, u32)>,
}

impl Page {
    /// Makes call `op` with its JSON `args` (`{}` when it takes none) and
    /// `bytes` (a file's, for the calls that take one). `progress(done,
    /// total)` hears of a render's rows as they finish.
    pub fn call(
        &mut self,
        op: &str,
        args: &str,
        bytes: &[u8],
        progress: &(dyn Fn(u32, u32) + Sync),
    ) -> Result<Reply> {
        let args = if args.trim().is_empty() { "{}" } else { args };
        let parse_err = || format!("the arguments of {op:?}");
        match op {
            "give" => {
                let Named { path } = serde_json::from_str(args).with_context(parse_err)?;
                let name = input_file::given_name(Path::new(&path));
                self.files.insert(name, Arc::from(bytes));
                Ok(Reply::Json(Value::Null))
            }
            "forget" => {
                self.files.clear();
                Ok(Reply::Json(Value::Null))
            }
            "load" => self.load(serde_json::from_str(args).with_context(parse_err)?),
            "options" => {
                let options: Options = serde_json::from_str(args).with_context(parse_err)?;
                options.settings(&self.scene()?.settings)?;
                self.options = options;
                self.pixel = None;
                Ok(Reply::Json(self.settings_json()?))
            }
            "render" => self.render(progress),
            "pixel" => {
                #[derive(Deserialize)]
                #[serde(deny_unknown_fields)]
                struct At {
                    x: u32,
                    y: u32,
                }
                let At { x, y } = serde_json::from_str(args).with_context(parse_err)?;
                let (scene, settings) = (self.scene()?, self.settings()?);
                let logged = self.work.log_for((x, y));
                let view = PixelView::record(scene, &settings, (x, y), self.caption()?, logged)?;
                let json = view.json(scene);
                self.pixel = Some(view);
                Ok(Reply::Json(json))
            }
            "ray" | "step" | "goto" | "diagram" => {
                let scene = self.loaded.as_ref().map(|l| &l.scene);
                let (Some(view), Some(scene)) = (self.pixel.as_mut(), scene) else {
                    bail!("no pixel is picked: click one first");
                };
                view.call(op, args, scene)
            }
            "compare" => {
                let Named { path } = serde_json::from_str(args).with_context(parse_err)?;
                let loaded = self.loaded.as_ref().context("no scene is open")?;
                let json = self
                    .work
                    .compare(&loaded.scene, &loaded.path, &path, bytes)?;
                Ok(Reply::Json(json))
            }
            "error_map" => Ok(Reply::Bytes(self.work.error_map_png()?)),
            "raylog" => {
                let Named { path } = serde_json::from_str(args).with_context(parse_err)?;
                let loaded = self.loaded.as_ref().context("no scene is open")?;
                let json = self
                    .work
                    .read_log(&loaded.scene, &loaded.path, &path, bytes)?;
                self.pixel = None;
                Ok(Reply::Json(json))
            }
            _ => bail!("the page has no call named {op:?}"),
        }
    }

    /// The diagram's title: the scene file's name and the options that
    /// change what is drawn, as `raystep diagram` names them.
    fn caption(&self) -> Result<Caption> {
        let loaded = self.loaded.as_ref().context("no scene is open")?;
        let scene = (loaded.path.file_name()).map_or_else(
            || loaded.path.display().to_string(),
            |n| n.to_string_lossy().into(),
        );
        let mut options: Vec<String> = loaded
            .size
            .iter()
            .map(|(w, h)| format!("--size {w}x{h}"))
            .collect();
        options.extend(
            self.options
                .mistakes
                .iter()
                .map(|m| format!("--mistake {m}")),
        );
        Ok(Caption { scene, options })
    }

    fn scene(&self) -> Result<&Scene> {
        Ok(&self.loaded.as_ref().context("no scene is open")?.scene)
    }

    /// The scene's settings under the page's toggles.
    fn settings(&self) -> Result<Settings> {
        self.options.settings(&self.scene()?.settings)
    }

    /// Reads the scene `path` from the given files (its meshes too), at
    /// `size` when given. The page's toggles go back to the scene's own.
    fn load(&mut self, args: LoadArgs) -> Result<Reply> {
        let path = input_file::given_name(Path::new(&args.path));
        let read = input_file::with_files(&self.files, || scene::load(&path));
        // The command line's words: "error: " and the message (main.rs).
        let mut scene =
            read.map_err(|e| anyhow::anyhow!(printable_text(&format!("{e:#}")).into_owned()))?;
        if let Some((width, height)) = args.size {
            scene = scene.with_size(width, height)?;
        }
        check_page_size(scene.width, scene.height)?;
        self.loaded = Some(Loaded {
            path,
            size: args.size,
            scene,
        });
        self.options = Options::default();
        self.pixel = None;
        self.work = StudentWork::default();
        let scene = self.scene()?;
        let warnings: Vec<String> = scene
            .warnings
            .iter()
            .map(|w| printable_text(w).into_owned())
            .collect();
        let mut json = json!({
            "width": scene.width,
            "height": scene.height,
            "objects": scene.objects.len(),
            "lights": scene.lights.len(),
            "warnings": warnings,
            "catalogue": catalogue(scene.settings.profile),
        });
        json["settings"] = self.settings_json()?;
        Ok(Reply::Json(json))
    }

    /// The toggles in force, for the page's controls, and the profile the
    /// scene is traced with when it is not the lecture's (as the debugger's
    /// header names it): `profile`, its name, `profile_words`, what
    /// `inspect` and `explain` say of it, and `refracts: false` where it
    /// casts no transmitted ray.
    fn settings_json(&self) -> Result<Value> {
        let settings = self.settings()?;
        let switches = settings.switches;
        let mut json = json!({
            "shadows": switches.shadows,
            "reflection": switches.reflection,
            "transmission": switches.transmission,
            "ambient": switches.ambient,
            "specular": match settings.specular {
                SpecularModel::Blinn => "blinn",
                SpecularModel::Phong => "phong",
            },
            "max_depth": settings.max_depth,
            "mistakes": settings.mistakes.iter().map(|m| m.name()).collect::<Vec<_>>(),
        });
        if let Some(words) = settings.profile.words() {
            json["profile"] = settings.profile.name().into();
            json["profile_words"] = words.into();
        }
        // No transmission to switch (cse167, MODEL §11): the page hides it.
        if !settings.profile.refracts() {
            json["refracts"] = false.into();
        }
        Ok(json)
    }

    /// The whole image as `raystep render` writes it: the same PNG bytes.
    fn render(&self, progress: &(dyn Fn(u32, u32) + Sync)) -> Result<Reply> {
        let (scene, settings) = (self.scene()?, self.settings()?);
        let total = scene.height;
        let done = std::sync::atomic::AtomicU32::new(0);
        let tick = || {
            let rows = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(rows, total);
        };
        let (image, NoRecorder) = render::<NoRecorder>(scene, &settings, &tick);
        let mut png = Vec::new();
        raystep_tools::output::write_png(&image, &mut std::io::Cursor::new(&mut png))?;
        Ok(Reply::Bytes(png))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::record::stepping;
    use raystep_engine::record::{explain, record_pixel};

    /// A page given `files` (paths below `scenes/`, as the page's bundle
    /// names them).
    fn page_with(files: &[&str]) -> Page {
        let mut page = Page::default();
        for file in files {
            let bytes = std::fs::read(format!("../../scenes/{file}")).unwrap();
            page.call(
                "give",
                &json!({ "path": file }).to_string(),
                &bytes,
                &|_, _| {},
            )
            .unwrap();
        }
        page
    }

    fn call(page: &mut Page, op: &str, args: Value) -> Result<Reply> {
        page.call(op, &args.to_string(), &[], &|_, _| {})
    }

    fn json_of(reply: Result<Reply>) -> Value {
        match reply.unwrap() {
            Reply::Json(json) => json,
            other => panic!("not JSON: {other:?}"),
        }
    }

    fn error_of(reply: Result<Reply>) -> String {
        format!("{:#}", reply.unwrap_err())
    }

    const CORNELL: [&str; 3] = [
        "cornell/cornell.toml",
        "cornell/cornell.obj",
        "cornell/cornell.mtl",
    ];

    #[test]
    fn a_scene_and_its_meshes_come_from_the_given_files_and_render_as_from_disk() {
        let mut page = page_with(&CORNELL);
        let loaded = json_of(call(
            &mut page,
            "load",
            json!({"path": "cornell/cornell.toml", "size": [48, 40]}),
        ));
        assert_eq!(
            (loaded["width"].as_u64(), loaded["height"].as_u64()),
            (Some(48), Some(40))
        );
        let rows = std::sync::Mutex::new(Vec::new());
        let Reply::Bytes(png) = page
            .call("render", "{}", &[], &|done, total| {
                rows.lock().unwrap().push((done, total))
            })
            .unwrap()
        else {
            panic!("a render is bytes")
        };
        // The same scene read from disk, rendered and encoded the one way.
        let disk = scene::load(Path::new("../../scenes/cornell/cornell.toml"))
            .unwrap()
            .with_size(48, 40)
            .unwrap();
        let (image, NoRecorder) = render::<NoRecorder>(&disk, &disk.settings, &|| {});
        let mut expected = Vec::new();
        raystep_tools::output::write_png(&image, &mut std::io::Cursor::new(&mut expected)).unwrap();
        assert!(png == expected, "the page's PNG differs from the engine's");
        // One progress report per row, the last saying all 40.
        let rows = rows.into_inner().unwrap();
        assert_eq!(rows.len(), 40);
        assert_eq!(rows.iter().max(), Some(&(40, 40)));
    }

    #[test]
    fn a_mesh_not_given_is_named_with_what_to_do() {
        let mut page = page_with(&CORNELL[..1]);
        let error = error_of(call(
            &mut page,
            "load",
            json!({"path": "cornell/cornell.toml"}),
        ));
        assert!(error.contains("cornell/cornell.obj"), "{error}");
        assert!(error.contains("open it together with the scene"), "{error}");
    }

    #[test]
    fn a_scene_error_is_told_at_its_line_and_column_as_the_command_line_tells_it() {
        let mut page = Page::default();
        // Line 2 opens an array it never closes: the TOML parser stops at
        // the end of the text, line 3, column 1 (after the last newline).
        let text = "[camera]\neye = [0, 0, 5\n";
        page.call(
            "give",
            r#"{"path": "bad.toml"}"#,
            text.as_bytes(),
            &|_, _| {},
        )
        .unwrap();
        let error = error_of(call(&mut page, "load", json!({"path": "bad.toml"})));
        let cli = format!(
            "{:#}",
            scene::parse(Path::new("bad.toml"), text).unwrap_err()
        );
        assert_eq!(error, printable_text(&cli));
        assert!(error.starts_with("bad.toml:2:"), "{error}");
    }

    #[test]
    fn sizes_past_the_pages_limit_are_refused_in_the_command_lines_words() {
        let mut page = page_with(&["glass.toml"]);
        let refuse = |page: &mut Page, size: [u32; 2]| {
            error_of(call(
                page,
                "load",
                json!({"path": "glass.toml", "size": size}),
            ))
        };
        // 4096 x 4096 = 16,777,216 pixels: four times the page's 2048 x 2048.
        assert_eq!(
            refuse(&mut page, [4096, 4096]),
            "image size 4096x4096 is too large for the page: at most 4194304 pixels \
             (2048 x 2048) are rendered in a browser; `raystep render` renders up to 8192 x 8192"
        );
        // What the command line refuses too, in its own words.
        assert_eq!(
            refuse(&mut page, [0, 10]),
            "image size 0x10 is empty: both sides must be at least 1"
        );
        assert!(
            call(
                &mut page,
                "load",
                json!({"path": "glass.toml", "size": [2048, 2048]})
            )
            .is_ok()
        );
    }

    #[test]
    fn a_pixel_is_recorded_under_the_toggles_and_stepped_like_the_debugger() {
        let mut page = page_with(&["seven-rays.toml"]);
        json_of(call(&mut page, "load", json!({"path": "seven-rays.toml"})));
        let outside = error_of(call(&mut page, "pixel", json!({"x": 10_000, "y": 0})));
        assert!(
            outside.starts_with("pixel (10000, 0) is outside the"),
            "{outside}"
        );
        let scene = scene::load(Path::new("../../scenes/seven-rays.toml")).unwrap();
        let (x, y) = (scene.width / 2, scene.height / 2);
        let view = json_of(call(&mut page, "pixel", json!({"x": x, "y": y})));
        let tree = record_pixel(&scene, &scene.settings, x, y);
        assert_eq!(view["rays"].as_u64(), Some(tree.nodes.len() as u64));
        assert_eq!(view["explain"].as_str(), Some(explain(&tree).as_str()));
        assert_eq!(
            view["events"].as_array().map(Vec::len),
            Some(tree.events.len())
        );
        // Into goes to the next ray cast, as the debugger's `i` does.
        let into = json_of(call(&mut page, "step", json!({"how": "into"})));
        let expected = stepping::step(&tree, 0, stepping::Step::Into);
        assert_eq!(into["at"].as_u64(), Some(expected as u64));
        assert_eq!(
            into["node"].as_u64(),
            Some(tree.events[expected].node as u64)
        );
        // No shadows: the pixel is recorded again without them.
        json_of(call(&mut page, "options", json!({"shadows": false})));
        let view = json_of(call(&mut page, "pixel", json!({"x": x, "y": y})));
        let settings = Settings {
            switches: raystep_engine::scene::Switches {
                shadows: false,
                ..scene.settings.switches
            },
            ..scene.settings
        };
        let unshadowed = record_pixel(&scene, &settings, x, y);
        assert_eq!(
            view["explain"].as_str(),
            Some(explain(&unshadowed).as_str())
        );
    }

    #[test]
    fn the_settings_name_a_profile_other_than_the_lectures_and_keep_it_under_the_toggles() {
        // A .test scene is CSE 167's (docs/CSE167.md); a .toml without
        // `profile` the lecture's, of which nothing is said (the debugger's
        // header says nothing of it either).
        let cse167 = "It is traced with the cse167 profile, CSE 167's equation (MODEL §11): \
                      ambient and emission added as they are, f_att not clamped, a light behind \
                      the surface still casts its shadow ray and adds its highlight, the mirror \
                      ray weighted by k_s O_s, and no refraction.";
        let mut page = page_with(&["cse167/mirrors.test", "glass.toml"]);
        let loaded = json_of(call(
            &mut page,
            "load",
            json!({"path": "cse167/mirrors.test"}),
        ));
        assert_eq!(loaded["settings"]["profile"], "cse167");
        assert_eq!(loaded["settings"]["profile_words"], cse167);
        // No refraction: the page hides its transmission switch.
        assert_eq!(loaded["settings"]["refracts"], false);
        // `maxdepth 4` is four bounces: MODEL's depth 5.
        assert_eq!(loaded["settings"]["max_depth"], 5);
        let toggled = json_of(call(&mut page, "options", json!({"max_depth": 2})));
        assert_eq!(toggled["profile"], "cse167");
        assert_eq!(toggled["max_depth"], 2);
        let lecture = json_of(call(&mut page, "load", json!({"path": "glass.toml"})));
        let keys: Vec<&str> = lecture["settings"]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        assert_eq!(
            keys,
            [
                "ambient",
                "max_depth",
                "mistakes",
                "reflection",
                "shadows",
                "specular",
                "transmission"
            ]
        );
    }
}
