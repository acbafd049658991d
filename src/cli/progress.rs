//! Progress of the long runs (verify, accuracy, reference, figures, batch) on standard
//! error, drawn only when standard error is a terminal and `--quiet` is not given: the
//! one progress display.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar over `total` steps with a message naming the current one.
pub struct Progress(ProgressBar);

impl Progress {
    pub fn new(total: usize) -> Self {
        let target = if super::report::quiet() {
            ProgressDrawTarget::hidden()
        } else {
            ProgressDrawTarget::stderr()
        };
        let bar = ProgressBar::with_draw_target(Some(total as u64), target);
        if let Ok(style) = ProgressStyle::with_template("[{pos}/{len}] {wide_msg} {elapsed}") {
            bar.set_style(style);
        }
        Progress(bar)
    }

    /// Step `done` of the total (0-based count of finished steps) is now `message`.
    pub fn at(&self, done: usize, message: &str) {
        self.0.set_position(done as u64);
        self.0.set_message(message.to_string());
    }

    /// Step `done` of `total` is now `message`, for work that learns its total as it goes.
    pub fn at_of(&self, done: usize, total: usize, message: &str) {
        self.0.set_length(total as u64);
        self.at(done, message);
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}
