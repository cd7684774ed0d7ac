//! The page's teaching toggles, as the debugger's keys set them: the
//! switches, Blinn or Phong, the maximum depth and the mistakes traced.

use anyhow::{Result, bail};
use serde::{Deserialize, Serialize};

use raystep_engine::scene::{DEEPEST_TOGGLED_DEPTH, Profile, Settings, SpecularModel};
use raystep_model::mistakes::{Mistake, Mistakes};

/// The toggles as the page sends them; what it leaves out is the scene's.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Options {
    pub(crate) shadows: Option<bool>,
    pub(crate) reflection: Option<bool>,
    pub(crate) transmission: Option<bool>,
    pub(crate) ambient: Option<bool>,
    /// "blinn" or "phong".
    pub(crate) specular: Option<String>,
    pub(crate) max_depth: Option<u32>,
    /// The catalogue's names (MODEL §8), as `--mistake` takes them.
    #[serde(default)]
    pub(crate) mistakes: Vec<String>,
}

impl Options {
    /// The scene's settings with these toggles; a name or depth out of
    /// range is refused, saying what is allowed.
    pub(crate) fn settings(&self, scene: &Settings) -> Result<Settings> {
        let mut settings = *scene;
        let switches = &mut settings.switches;
        for (flag, value) in [
            (&mut switches.shadows, self.shadows),
            (&mut switches.reflection, self.reflection),
            (&mut switches.transmission, self.transmission),
            (&mut switches.ambient, self.ambient),
        ] {
            if let Some(value) = value {
                *flag = value;
            }
        }
        settings.specular = match self.specular.as_deref() {
            None => scene.specular,
            Some("blinn") => SpecularModel::Blinn,
            Some("phong") => SpecularModel::Phong,
            Some(other) => bail!("specular model {other:?}: it is \"blinn\" or \"phong\""),
        };
        if let Some(depth) = self.max_depth {
            if !(1..=DEEPEST_TOGGLED_DEPTH).contains(&depth) {
                bail!("max depth {depth}: it goes from 1 to {DEEPEST_TOGGLED_DEPTH}");
            }
            settings.max_depth = depth;
        }
        settings.mistakes = self
            .mistakes
            .iter()
            .map(|name| mistake_named(name))
            .collect::<Result<Mistakes>>()?;
        // As `--mistake` refuses it: the page's menu does not list it.
        let profile = scene.profile;
        if let Some((mistake, why)) =
            (settings.mistakes.iter()).find_map(|m| Some((m, profile.why_not_offered(m)?)))
        {
            bail!("mistake {mistake} {why}");
        }
        Ok(settings)
    }
}

fn mistake_named(name: &str) -> Result<Mistake> {
    match Mistake::ALL.iter().find(|m| m.name() == name) {
        Some(&mistake) => Ok(mistake),
        None => bail!("no mistake is named {name:?} (MODEL §8 lists them)"),
    }
}

/// The catalogue for the page's menu: the name and summary of each
/// mistake the scene's `profile` offers (`Profile::offers`).
pub(crate) fn catalogue(profile: Profile) -> Vec<(&'static str, &'static str)> {
    (profile.offered_mistakes())
        .map(|m| (m.name(), m.summary()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toggles_change_only_what_they_name() {
        let scene = Settings::default();
        let options: Options = serde_json::from_str(
            r#"{"shadows": false, "specular": "phong", "max_depth": 2,
                "mistakes": ["eta-inverted", "flipped-y"]}"#,
        )
        .unwrap();
        let settings = options.settings(&scene).unwrap();
        assert!(!settings.switches.shadows);
        assert!(settings.switches.reflection && settings.switches.ambient);
        assert_eq!(settings.specular, SpecularModel::Phong);
        assert_eq!(settings.max_depth, 2);
        let expected = Mistakes::NONE
            .with(Mistake::EtaInverted)
            .with(Mistake::FlippedY);
        assert_eq!(settings.mistakes, expected);
        assert_eq!(settings.background, scene.background);
        // Nothing given: the scene's own settings.
        assert_eq!(Options::default().settings(&scene).unwrap(), scene);
    }

    #[test]
    fn out_of_range_toggles_are_refused_with_what_is_allowed() {
        let refuse = |json: &str| {
            let options: Options = serde_json::from_str(json).unwrap();
            options
                .settings(&Settings::default())
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            refuse(r#"{"max_depth": 17}"#),
            "max depth 17: it goes from 1 to 16"
        );
        assert!(refuse(r#"{"mistakes": ["eta-invert"]}"#).contains("\"eta-invert\""));
        assert!(refuse(r#"{"specular": "cook"}"#).contains("\"blinn\" or \"phong\""));
    }

    #[test]
    fn a_cse167_scene_lists_and_takes_only_the_mistakes_it_offers() {
        // No refraction under cse167 (MODEL §11): 22 - 3 = 19 listed.
        let names: Vec<&str> = (catalogue(Profile::Cse167).iter()).map(|c| c.0).collect();
        assert_eq!(names.len(), 19);
        for gone in ["eta-inverted", "tir-dropped", "refraction-outward-normal"] {
            assert!(!names.contains(&gone), "{gone}");
        }
        assert!(names.contains(&"opaque-shadows"));
        assert_eq!(catalogue(Profile::Lecture).len(), Mistake::ALL.len());
        let scene = Settings {
            profile: Profile::Cse167,
            ..Settings::default()
        };
        let options: Options =
            serde_json::from_str(r#"{"mistakes": ["gamma", "tir-dropped"]}"#).unwrap();
        assert_eq!(
            options.settings(&scene).unwrap_err().to_string(),
            "mistake tir-dropped has no meaning under the cse167 profile: \
             it has no refraction (MODEL §11)"
        );
    }
}
