//! The clock that drives an animated lab's `time` (the originals' `glutIdleFunc` advancing it),
//! shared by the window and the web page. It reads no time itself: the caller passes seconds
//! from any origin it likes (the window's start, the page's `performance.now()`), so it works
//! the same on every platform and is tested without waiting.

use crate::lab::Lab;

/// An animated lab's clock: `time` follows the caller's seconds (times a scale), Space pauses it,
/// and a lab that sets its own time (a restart key, a parameter) moves the clock's origin
/// instead of being overwritten.
#[derive(Clone, Debug)]
pub struct Clock {
    scale: f64,
    /// The caller's second it started at.
    start: f64,
    /// The lab's time at the caller's second 0.
    offset: f64,
    paused: bool,
    /// The time the clock last wrote, to notice a lab that set its own.
    last: Option<f64>,
}

impl Clock {
    /// A clock that starts from the lab's current `time` at the caller's second `now`; `scale`
    /// seconds of `time` pass per second (1 in use; the window tests speed it up).
    pub fn new(lab: &dyn Lab, now: f64, scale: f64) -> Clock {
        let time = if lab.params().has("time") {
            lab.params().f64("time")
        } else {
            0.0
        };
        Clock {
            scale,
            start: now,
            offset: time - now * scale,
            paused: false,
            last: None,
        }
    }

    /// The clock started anew at the same second, from the lab's `time` now (its parameters
    /// were replaced before the first frame), paused as it was.
    pub fn restarted(&self, lab: &dyn Lab) -> Clock {
        Clock {
            paused: self.paused,
            ..Clock::new(lab, self.start, self.scale)
        }
    }

    /// A clock that starts paused (a shared link that names a moment).
    pub fn paused(mut self) -> Clock {
        self.paused = true;
        self
    }

    /// Whether the clock drives the lab now: an animated lab with a `time`, not paused.
    pub fn runs(&self, lab: &dyn Lab) -> bool {
        lab.animated() && lab.params().has("time") && !self.paused
    }

    /// Whether Space paused it.
    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Sets the lab's `time` for the caller's second `now` (nothing when it does not run).
    pub fn tick(&mut self, lab: &mut dyn Lab, now: f64) {
        if !self.runs(lab) {
            return;
        }
        let current = lab.params().f64("time");
        if self.last.is_some_and(|t| t != current) {
            self.offset = current - now * self.scale;
        }
        lab.params_mut()
            .set_unchecked("time", &[self.offset + now * self.scale]);
        self.last = Some(lab.params().f64("time"));
    }

    /// Space: pauses or resumes the clock of an animated lab, keeping its time; returns whether
    /// it did anything (a lab that is not animated ignores Space here).
    pub fn toggle(&mut self, lab: &dyn Lab, now: f64) -> bool {
        if !lab.animated() {
            return false;
        }
        if self.paused && lab.params().has("time") {
            self.offset = lab.params().f64("time") - now * self.scale;
            self.last = None;
        }
        self.paused = !self.paused;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::{Input, LabInfo};
    use crate::params::{ParamSpec, Params};
    use crate::render::Frame;

    static INFO: LabInfo = LabInfo::new("clocked", "t", "t", "t", (4, 4), crate::lab::Keys::text(""));

    struct Clocked(Params);
    impl Lab for Clocked {
        fn info(&self) -> &'static LabInfo {
            &INFO
        }
        fn params(&self) -> &Params {
            &self.0
        }
        fn params_mut(&mut self) -> &mut Params {
            &mut self.0
        }
        fn input(&mut self, _: Input) -> bool {
            false
        }
        fn reload(&mut self, _: &crate::lab::BuildContext) -> crate::error::Result<()> {
            Ok(())
        }
        fn render(&mut self, _: &mut Frame<'_>) -> crate::error::Result<()> {
            Ok(())
        }
        fn animated(&self) -> bool {
            true
        }
    }

    fn lab(time: f64) -> Clocked {
        let mut p = Params::new(&[ParamSpec::real("time", &[0.0], 0.0, 1e9, "seconds")]);
        p.set_unchecked("time", &[time]);
        Clocked(p)
    }

    #[test]
    fn time_follows_the_callers_seconds_from_the_labs_own_start() {
        let mut lab = lab(2.0);
        let mut clock = Clock::new(&lab, 100.0, 1.0);
        clock.tick(&mut lab, 101.5);
        assert_eq!(lab.params().f64("time"), 3.5);
        let mut fast = Clock::new(&lab, 0.0, 4.0);
        fast.tick(&mut lab, 0.5);
        assert_eq!(lab.params().f64("time"), 5.5);
    }

    #[test]
    fn space_pauses_and_resumes_where_it_stopped() {
        let mut lab = lab(0.0);
        let mut clock = Clock::new(&lab, 0.0, 1.0);
        clock.tick(&mut lab, 1.0);
        assert!(clock.toggle(&lab, 1.0));
        clock.tick(&mut lab, 5.0);
        assert_eq!(lab.params().f64("time"), 1.0, "paused: time stands");
        clock.toggle(&lab, 5.0);
        clock.tick(&mut lab, 6.0);
        assert_eq!(lab.params().f64("time"), 2.0, "resumed from 1, one second later");
    }

    #[test]
    fn a_time_the_lab_set_itself_moves_the_origin() {
        let mut lab = lab(0.0);
        let mut clock = Clock::new(&lab, 0.0, 1.0);
        clock.tick(&mut lab, 1.0);
        lab.params_mut().set_unchecked("time", &[10.0]);
        clock.tick(&mut lab, 1.0);
        assert_eq!(lab.params().f64("time"), 10.0);
        clock.tick(&mut lab, 2.0);
        assert_eq!(lab.params().f64("time"), 11.0);
        let stopped = Clock::new(&lab, 0.0, 1.0).paused();
        assert!(stopped.is_paused() && !stopped.runs(&lab));
    }

    #[test]
    fn a_restarted_clock_starts_from_the_new_time_at_the_same_second_and_scale() {
        let mut lab = lab(0.0);
        let clock = Clock::new(&lab, 10.0, 2.0);
        lab.params_mut().set_unchecked("time", &[7.0]);
        let mut restarted = clock.restarted(&lab);
        restarted.tick(&mut lab, 11.0);
        assert_eq!(lab.params().f64("time"), 9.0, "7 at second 10, two per second");
        assert!(
            Clock::new(&lab, 0.0, 1.0).paused().restarted(&lab).is_paused(),
            "paused as it was"
        );
    }
}
