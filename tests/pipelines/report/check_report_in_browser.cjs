// Loads a run's report (RUN/report/index.html) in headless Chromium through
// playwright-core (Debian's chromium, no browser download) and fails unless:
//   - the page makes no request but for itself (every request is recorded;
//     the page's Content-Security-Policy would also block one, and a blocked
//     request is a console error);
//   - nothing is written to the console as an error, and no script throws;
//   - every plot rendered: the page marks <body data-plots="rendered">, and
//     each .vega-plot holds an <svg> with at least one drawn mark;
//   - every section the run's files call for is there.
// Then writes a full-page screenshot.
//
//   node check_report_in_browser.cjs NODE_MODULES REPORT_HTML SCREENSHOT_PNG [--expect-metrics]
'use strict';
const path = require('path');
const [modules, report, screenshot, ...flags] = process.argv.slice(2);
if (!modules || !report || !screenshot) {
  console.error('usage: node check_report_in_browser.cjs NODE_MODULES REPORT_HTML SCREENSHOT_PNG [--expect-metrics]');
  process.exit(2);
}
const {chromium} = require(path.join(modules, 'playwright-core'));
const executablePath = process.env.HSMAP_CHROMIUM || '/usr/bin/chromium';
const expectMetrics = flags.includes('--expect-metrics');

(async () => {
  const failures = [];
  const browser = await chromium.launch({
    executablePath,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--host-resolver-rules=MAP * ~NOTFOUND'],
  });
  try {
    const page = await browser.newPage({viewport: {width: 1400, height: 1000}});
    const pageUrl = 'file://' + path.resolve(report);
    page.on('request', (request) => {
      if (request.url() !== pageUrl) failures.push('request: ' + request.method() + ' ' + request.url().slice(0, 200));
    });
    page.on('console', (message) => {
      if (message.type() === 'error') failures.push('console error: ' + message.text());
    });
    page.on('pageerror', (error) => failures.push('script error: ' + error.message));
    await page.goto(pageUrl, {waitUntil: 'load'});
    await page.waitForFunction(() => document.body.dataset.plots === 'rendered' || document.body.dataset.plots === 'failed',
                               null, {timeout: 30000});
    const state = await page.evaluate(() => {
      const plots = [...document.querySelectorAll('.vega-plot')].map((div) => {
        const svg = div.querySelector('svg');
        const marks = svg ? svg.querySelectorAll('g.role-mark > *, g.mark-image image').length : 0;
        return {name: div.dataset.plot, svg: !!svg, marks};
      });
      return {
        plots,
        status: document.body.dataset.plots,
        expected: Number(document.body.dataset.plotsExpected),
        sections: [...document.querySelectorAll('main > section')].map((s) => s.id),
        images: [...document.querySelectorAll('img')].map((img) => ({src: img.src.slice(0, 22), loaded: img.complete && img.naturalWidth > 0})),
        metricsRows: document.querySelectorAll('#truth table tbody tr').length,
      };
    });
    if (state.status !== 'rendered') failures.push('the page says its plots did not render: ' + state.status);
    if (state.plots.length === 0) failures.push('no plot on the page');
    if (state.plots.length !== state.expected) failures.push(state.plots.length + ' plots, the page expected ' + state.expected);
    for (const plot of state.plots) {
      if (!plot.svg) failures.push('plot ' + plot.name + ' has no <svg>');
      else if (plot.marks === 0) failures.push('plot ' + plot.name + ' has an <svg> without marks');
    }
    const required = ['run', 'trajectory', 'residuals', 'calibration', 'ortho', 'mesh', 'truth'];
    for (const id of required) if (!state.sections.includes(id)) failures.push('section #' + id + ' is missing');
    const requiredPlots = ['stage-times', 'stage-memory', 'plan-view', 'depth-profile', 'altitude-profile', 'histogram-0', 'spectra'];
    if (expectMetrics) requiredPlots.push('ortho-displacements');
    for (const name of requiredPlots) if (!state.plots.some((p) => p.name === name)) failures.push('plot ' + name + ' is missing');
    for (const image of state.images) {
      if (!image.src.startsWith('data:image/')) failures.push('an image is not inlined: ' + image.src);
      if (!image.loaded) failures.push('an image did not decode: ' + image.src);
    }
    if (expectMetrics && state.metricsRows === 0) failures.push('no metrics table although metrics.json exists');
    await page.screenshot({path: screenshot, fullPage: true});
    console.log('plots: ' + state.plots.map((p) => p.name + ' (' + p.marks + ' marks)').join(', '));
    console.log('sections: ' + state.sections.join(', ') + '; screenshot: ' + screenshot);
  } finally {
    await browser.close();
  }
  if (failures.length) {
    for (const failure of failures) console.error('FAIL: ' + failure);
    process.exit(1);
  }
  console.log('report OK: no request, no console error, every plot rendered');
})().catch((error) => {
  console.error('FAIL: ' + (error && error.stack || error));
  process.exit(1);
});
