//! Plots as SVG: line plots on linear or logarithmic axes, and bar charts. Text uses
//! the reader's own sans-serif font: the files load nothing.

use std::fmt::Write as _;

const WIDTH: f64 = 640.0;
const HEIGHT: f64 = 400.0;
const LEFT: f64 = 78.0;
const RIGHT: f64 = 24.0;
const TOP: f64 = 44.0;
const BOTTOM: f64 = 64.0;
/// Series colours, distinct in colour and in lightness.
const COLOURS: [&str; 5] = ["#1f5fa8", "#c8501e", "#2a8a3e", "#7a3fa0", "#8a6d1a"];

pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

#[derive(Clone, Copy)]
pub enum Scale {
    Linear,
    Log,
}

pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: Scale,
    pub y_scale: Scale,
    pub series: Vec<Series>,
}

/// One axis: data range to pixels.
struct Axis {
    scale: Scale,
    low: f64,
    high: f64,
    from: f64,
    to: f64,
}

impl Axis {
    fn new(scale: Scale, values: impl Iterator<Item = f64>, from: f64, to: f64) -> Axis {
        let values: Vec<f64> = values
            .filter(|v| v.is_finite() && (matches!(scale, Scale::Linear) || *v > 0.0))
            .collect();
        let (mut low, mut high) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                (l.min(v), h.max(v))
            });
        if values.is_empty() {
            (low, high) = (1.0, 10.0);
        }
        match scale {
            Scale::Log => {
                low = 10f64.powf(low.log10().floor());
                high = 10f64.powf(high.log10().ceil().max(low.log10() + 1.0));
            }
            Scale::Linear => {
                let step = nice_step(high - low.min(0.0));
                low = (low.min(0.0) / step).floor() * step;
                high = ((high / step).ceil() * step).max(low + step);
            }
        }
        Axis {
            scale,
            low,
            high,
            from,
            to,
        }
    }

    fn at(&self, v: f64) -> f64 {
        let t = match self.scale {
            Scale::Linear => (v - self.low) / (self.high - self.low),
            Scale::Log => (v.log10() - self.low.log10()) / (self.high.log10() - self.low.log10()),
        };
        self.from + t * (self.to - self.from)
    }

    fn ticks(&self) -> Vec<f64> {
        match self.scale {
            Scale::Log => {
                let (a, b) = (
                    self.low.log10().round() as i32,
                    self.high.log10().round() as i32,
                );
                (a..=b).map(|e| 10f64.powi(e)).collect()
            }
            Scale::Linear => {
                let step = nice_step(self.high - self.low);
                let n = ((self.high - self.low) / step).round() as i32;
                (0..=n).map(|i| self.low + i as f64 * step).collect()
            }
        }
    }
}

/// A round step giving about five intervals over `span`.
fn nice_step(span: f64) -> f64 {
    let raw = (span / 5.0).max(f64::MIN_POSITIVE);
    let magnitude = 10f64.powf(raw.log10().floor());
    let m = raw / magnitude;
    magnitude
        * if m <= 1.0 {
            1.0
        } else if m <= 2.0 {
            2.0
        } else if m <= 5.0 {
            5.0
        } else {
            10.0
        }
}

fn label(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        let e = v.abs().log10().round() as i32;
        if (v.abs() - 10f64.powi(e)).abs() < 1e-9 * v.abs() {
            return format!("1e{e}");
        }
        return format!("{v:.0e}");
    }
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn header(out: &mut String, title: &str) {
    let _ = write!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="13"><title>{t}</title><rect width="100%" height="100%" fill="#fff"/><text x="{x}" y="24" text-anchor="middle" font-size="15" font-weight="bold">{t}</text>"##,
        t = escape(title),
        x = WIDTH / 2.0
    );
}

impl LinePlot {
    pub fn svg(&self) -> String {
        let points = || self.series.iter().flat_map(|s| s.points.iter());
        let x = Axis::new(self.x_scale, points().map(|p| p.0), LEFT, WIDTH - RIGHT);
        let y = Axis::new(self.y_scale, points().map(|p| p.1), HEIGHT - BOTTOM, TOP);
        let mut out = String::new();
        header(&mut out, &self.title);
        axes(&mut out, Some(&x), &y, &self.x_label, &self.y_label);
        for (i, s) in self.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let shown: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|(a, b)| {
                    let positive = |v: f64, scale| matches!(scale, Scale::Linear) || v > 0.0;
                    a.is_finite() && b.is_finite() && positive(*a, x.scale) && positive(*b, y.scale)
                })
                .map(|&(a, b)| (x.at(a), y.at(b)))
                .collect();
            let path: Vec<String> = shown
                .iter()
                .map(|(a, b)| format!("{a:.1},{b:.1}"))
                .collect();
            let _ = write!(
                out,
                r#"<polyline fill="none" stroke="{colour}" stroke-width="2" points="{}"/>"#,
                path.join(" ")
            );
            // Markers only where they can be told apart.
            if shown.len() <= 40 {
                for (a, b) in &shown {
                    let _ = write!(
                        out,
                        r#"<circle cx="{a:.1}" cy="{b:.1}" r="3" fill="{colour}"/>"#
                    );
                }
            }
            // The legend, top right, on white over the curves.
            let ly = TOP + 8.0 + 18.0 * i as f64;
            let lx = WIDTH - RIGHT - 8.0;
            let text_width = 7.0 * s.name.chars().count() as f64;
            let _ = write!(
                out,
                r##"<rect x="{}" y="{}" width="{}" height="18" fill="#fff" fill-opacity="0.85"/>"##,
                lx - 34.0 - text_width,
                ly - 9.0,
                40.0 + text_width,
            );
            let _ = write!(
                out,
                r#"<line x1="{}" y1="{ly}" x2="{}" y2="{ly}" stroke="{colour}" stroke-width="2"/><text x="{}" y="{}" text-anchor="end">{}</text>"#,
                lx - 20.0,
                lx,
                lx - 26.0,
                ly + 4.0,
                escape(&s.name)
            );
        }
        out.push_str("</svg>\n");
        out
    }
}

/// The axes and grid; a bar chart has no x axis (its bars carry their labels).
fn axes(out: &mut String, x: Option<&Axis>, y: &Axis, x_label: &str, y_label: &str) {
    let _ = write!(
        out,
        r##"<g stroke="#888" stroke-width="1"><line x1="{LEFT}" y1="{b}" x2="{r}" y2="{b}"/><line x1="{LEFT}" y1="{TOP}" x2="{LEFT}" y2="{b}"/></g>"##,
        b = HEIGHT - BOTTOM,
        r = WIDTH - RIGHT
    );
    for (t, px) in x
        .iter()
        .flat_map(|x| x.ticks().into_iter().map(|t| (t, x.at(t))))
    {
        let _ = write!(
            out,
            r##"<line x1="{px:.1}" y1="{TOP}" x2="{px:.1}" y2="{b}" stroke="#e4e4e4"/><text x="{px:.1}" y="{ty}" text-anchor="middle">{}</text>"##,
            label(t),
            b = HEIGHT - BOTTOM,
            ty = HEIGHT - BOTTOM + 18.0
        );
    }
    for t in y.ticks() {
        let py = y.at(t);
        let _ = write!(
            out,
            r##"<line x1="{LEFT}" y1="{py:.1}" x2="{r}" y2="{py:.1}" stroke="#e4e4e4"/><text x="{tx}" y="{ty:.1}" text-anchor="end">{}</text>"##,
            label(t),
            r = WIDTH - RIGHT,
            tx = LEFT - 6.0,
            ty = py + 4.0
        );
    }
    let _ = write!(
        out,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text><text transform="translate(18 {}) rotate(-90)" text-anchor="middle">{}</text>"#,
        (LEFT + WIDTH - RIGHT) / 2.0,
        HEIGHT - 16.0,
        escape(x_label),
        (TOP + HEIGHT - BOTTOM) / 2.0,
        escape(y_label)
    );
}

pub struct BarChart {
    pub title: String,
    pub y_label: String,
    pub bars: Vec<(String, f64)>,
}

impl BarChart {
    pub fn svg(&self) -> String {
        let y = Axis::new(
            Scale::Linear,
            self.bars.iter().map(|b| b.1),
            HEIGHT - BOTTOM,
            TOP,
        );
        let mut out = String::new();
        header(&mut out, &self.title);
        let n = self.bars.len().max(1) as f64;
        let slot = (WIDTH - RIGHT - LEFT) / n;
        axes(&mut out, None, &y, "", &self.y_label);
        for (i, (name, value)) in self.bars.iter().enumerate() {
            let top = y.at(*value);
            let left = LEFT + slot * (i as f64 + 0.2);
            let _ = write!(
                out,
                r#"<rect x="{left:.1}" y="{top:.1}" width="{:.1}" height="{:.1}" fill="{}"/><text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text><text x="{:.1}" y="{:.1}" text-anchor="middle" font-size="12">{}</text>"#,
                slot * 0.6,
                (HEIGHT - BOTTOM - top).max(0.0),
                COLOURS[0],
                left + slot * 0.3,
                HEIGHT - BOTTOM + 18.0,
                escape(name),
                left + slot * 0.3,
                top - 6.0,
                label(*value)
            );
        }
        out.push_str("</svg>\n");
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axes_cover_the_data_by_whole_decades() {
        let axis = Axis::new(Scale::Log, [0.003, 0.2].into_iter(), 0.0, 100.0);
        assert_eq!(axis.ticks(), [1e-3, 1e-2, 1e-1, 1.0]);
        assert!(axis.at(1e-3).abs() < 1e-9 && (axis.at(1.0) - 100.0).abs() < 1e-9);
        assert!((axis.at(0.01) - 100.0 / 3.0).abs() < 1e-9);
    }

    #[test]
    fn linear_axes_start_at_zero_with_round_steps() {
        let axis = Axis::new(Scale::Linear, [0.04, 0.2241].into_iter(), 0.0, 1.0);
        assert_eq!(axis.low, 0.0);
        assert!((axis.high - 0.25).abs() < 1e-12, "{}", axis.high);
        assert_eq!(axis.ticks().len(), 6);
    }

    #[test]
    fn a_plot_draws_every_series_and_escapes_text() {
        let series = |name: &str, points: Vec<(f64, f64)>| Series {
            name: name.into(),
            points,
        };
        let svg = LinePlot {
            title: "a < b".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Linear,
            series: vec![
                series("one", vec![(1.0, 1.0), (10.0, 2.0)]),
                series("two", vec![(1.0, 3.0), (100.0, 0.5)]),
            ],
        }
        .svg();
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert_eq!(svg.matches("<circle").count(), 4);
        assert!(svg.contains("a &lt; b") && !svg.contains("a < b"));
    }
}
