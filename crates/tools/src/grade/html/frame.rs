//! The frame every page of the report shares: the document around a body,
//! and the one style sheet, inline, so that a page works from `file://`
//! with no network, on a laptop screen and on paper.

use super::escape::escape;

/// A whole HTML document titled `title` (plain text) around `body`; `wide`
/// pages (the class table) print in landscape.
pub(super) fn page(title: &str, body: &str, wide: bool) -> String {
    let orientation = if wide { "landscape" } else { "portrait" };
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>{}</title><style>{STYLE}@page{{size:A4 {orientation};margin:10mm}}</style></head>\
         <body>{body}</body></html>\n",
        escape(title)
    )
}

/// Colours: green a match, pale green with a green edge a near match,
/// amber a mistake, slate an unexplained difference, red a refusal (the
/// tags, the bars). System fonts only.
const STYLE: &str = "\
:root{--ink:#1c1e21;--muted:#5b6169;--line:#d5d9de;--head:#eef1f5;--stripe:#f7f8fa;\
--match:#1e7b34;--near:#cce8d3;--mistake:#b45309;--unexplained:#5b6b7a;--refused:#b3261e}\
*{box-sizing:border-box}\
html{-webkit-print-color-adjust:exact;print-color-adjust:exact}\
body{margin:0;padding:14px 18px 32px;color:var(--ink);background:#fff;\
font:14px/1.4 system-ui,-apple-system,\"Segoe UI\",Roboto,\"Noto Sans\",\"DejaVu Sans\",sans-serif}\
h1{font-size:1.45rem;margin:0 0 2px;overflow-wrap:anywhere}\
h2{font-size:1.1rem;margin:18px 0 6px;overflow-wrap:anywhere}\
a{color:#0b57d0}\
.summary{margin:2px 0 10px;color:var(--muted)}.summary b{color:var(--ink)}\
.note{margin:4px 0 8px;color:var(--muted);font-size:13px;max-width:120ch}\
.notes{font-size:12px;color:var(--muted);overflow-wrap:anywhere}p.notes{font-size:13px;color:var(--ink)}\
.grades .notes{display:-webkit-box;-webkit-box-orient:vertical;-webkit-line-clamp:3;overflow:hidden}\
.sub{display:block;font-weight:normal;font-size:12px;color:var(--muted)}\
h2 .sub{display:inline;margin-left:8px}\
img.px{image-rendering:pixelated;display:block;background:#e8eaed}\
.noimg{display:flex;align-items:center;justify-content:center;flex:none;color:var(--muted);\
font-size:11px;border:1px dashed #b9bec4;background:#f3f4f6}\
.tag{display:inline-block;padding:0 5px;border-radius:3px;font-size:12px;font-weight:600;\
color:#fff;white-space:nowrap}\
.tag.match{background:var(--match)}.tag.mistake{background:var(--mistake)}\
.tag.unexplained{background:var(--unexplained)}.tag.refused{background:var(--refused)}\
.tag.near{background:var(--near);color:#14532d;box-shadow:inset 0 0 0 1px var(--match)}\
.pts{font-variant-numeric:tabular-nums;white-space:nowrap}\
table.grades{border-collapse:separate;border-spacing:0;border-left:1px solid var(--line);border-top:1px solid var(--line)}\
.grades th,.grades td{border-bottom:1px solid var(--line);border-right:1px solid var(--line);\
padding:5px 7px;vertical-align:top;text-align:left;background:#fff}\
.grades tbody tr:nth-child(even)>*{background:var(--stripe)}\
.grades thead th{position:sticky;top:0;z-index:2;background:var(--head);font-size:13px}\
.grades th.student{position:sticky;left:0;z-index:1;min-width:9em;max-width:14em;font-weight:normal}\
.grades thead th.student{z-index:3}\
.grades th.scene{overflow-wrap:anywhere}\
a.sort{color:inherit;text-decoration:none}.grades th.total a.sort{white-space:nowrap}a.sort:hover{text-decoration:underline}\
a.sort::after{content:\" \\2195\";color:var(--muted);font-weight:normal}\
th[aria-sort=ascending] a.sort::after{content:\" \\25B2\";color:var(--ink)}\
th[aria-sort=descending] a.sort::after{content:\" \\25BC\";color:var(--ink)}\
.grades tbody tr{scroll-margin-top:110px}.grades tbody tr:target>*{background:#fff4c2}\
.grades th.student a{display:-webkit-box;-webkit-box-orient:vertical;-webkit-line-clamp:3;\
overflow:hidden;overflow-wrap:anywhere}\
.grades .total{text-align:right;font-size:15px}\
.thumbs{display:flex;gap:3px;text-decoration:none}\
.result{margin-top:3px}.result .tag{white-space:normal;overflow-wrap:anywhere}\
.flip{font-size:12px;color:var(--muted)}\
.overridden{font-size:12px;font-weight:600;max-width:var(--cell,204px);overflow-wrap:anywhere}\
p.overridden{font-size:14px;max-width:none}\
.reason{font-size:12px;color:var(--refused);max-width:var(--cell,204px);overflow-wrap:anywhere;\
display:-webkit-box;-webkit-box-orient:vertical;-webkit-line-clamp:3;overflow:hidden}\
p.reason{display:block;font-size:14px;max-width:none;overflow:visible}\
.cards{display:flex;flex-wrap:wrap;gap:10px 14px}\
figure.card{margin:0;padding:6px 10px;border:1px solid var(--line);border-radius:4px}\
figure.card figcaption{font-weight:600;font-size:13px;color:var(--ink);overflow-wrap:anywhere}\
svg.histogram{display:block}\
svg.histogram text{font:12px ui-monospace,\"DejaVu Sans Mono\",Menlo,Consolas,monospace;fill:var(--ink)}\
svg.histogram .match rect{fill:var(--match)}svg.histogram .mistake rect{fill:var(--mistake)}\
svg.histogram .unexplained rect{fill:var(--unexplained)}svg.histogram .refused rect{fill:var(--refused)}\
svg.histogram .near rect{fill:var(--near);stroke:var(--match)}\
details.who{margin-top:4px;font-size:12px;max-width:420px}details.who summary{cursor:pointer;color:var(--muted)}\
details.who dl{margin:4px 0 0}details.who dt{font-weight:600;margin-top:3px}\
details.who dd{margin:0 0 0 12px;overflow-wrap:anywhere}\
.files{margin:2px 0 8px}\
.back{margin:0 0 8px}\
.contents{padding-left:20px;margin:6px 0}.contents li{margin:2px 0}\
section.scene{border-top:1px solid var(--line);margin-top:14px}\
.images{display:flex;flex-wrap:wrap;gap:12px}\
.images figure{margin:0}.images img.px,.images .noimg{max-width:100%;height:auto}\
figcaption{font-size:12px;color:var(--muted)}\
.named{margin:8px 0}.named .tag{margin-right:4px}\
.rule{margin:2px 0;font-size:13px;color:var(--muted)}\
pre.report{white-space:pre-wrap;overflow-wrap:anywhere;background:#f6f8fa;border:1px solid var(--line);\
padding:8px 10px;max-width:120ch;font:12px/1.35 ui-monospace,\"DejaVu Sans Mono\",Menlo,Consolas,monospace}\
@media print{body{padding:0;font-size:11px}\
.grades thead th,.grades th.student{position:static}\
.grades tr,section.scene,figure.card,pre.report{break-inside:avoid}\
a{color:inherit;text-decoration:none}nav.back{display:none}\
.reason,.grades .notes{display:block;overflow:visible}}";
