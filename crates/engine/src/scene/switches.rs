//! The teaching switches: terms of the illumination model a teacher turns
//! off to show what each contributes. They are not part of the model; all
//! are on unless the debugger turns one off. A `Switch` names one; the
//! tracer reads the set, `Switches`.

use serde::Serialize;

/// The deepest max_depth the debugger's and the page's depth toggles go
/// to (a glass scene's tree doubles with every level).
pub const DEEPEST_TOGGLED_DEPTH: u32 = 16;

/// One teaching switch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Switch {
    Shadows,
    Reflection,
    Transmission,
    Ambient,
}

impl Switch {
    pub fn name(self) -> &'static str {
        match self {
            Switch::Shadows => "shadows",
            Switch::Reflection => "reflection",
            Switch::Transmission => "transmission",
            Switch::Ambient => "ambient",
        }
    }
}

/// Which switches are on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Switches {
    pub shadows: bool,
    pub reflection: bool,
    pub transmission: bool,
    pub ambient: bool,
}

impl Default for Switches {
    fn default() -> Self {
        Self {
            shadows: true,
            reflection: true,
            transmission: true,
            ambient: true,
        }
    }
}

impl Switches {
    /// Turns `switch` over; true when it is now on.
    pub fn flip(&mut self, switch: Switch) -> bool {
        let flag = match switch {
            Switch::Shadows => &mut self.shadows,
            Switch::Reflection => &mut self.reflection,
            Switch::Transmission => &mut self.transmission,
            Switch::Ambient => &mut self.ambient,
        };
        *flag = !*flag;
        *flag
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flipping_turns_one_switch_over_and_back() {
        let mut switches = Switches::default();
        assert!(!switches.flip(Switch::Transmission));
        assert_eq!(
            switches,
            Switches {
                transmission: false,
                ..Switches::default()
            }
        );
        assert!(switches.flip(Switch::Transmission));
        assert_eq!(switches, Switches::default());
    }
}
