// hsmap run report: builds the page from the run's data (the JSON element
// #hsmap-data, written by pipelines/report/report_json.cc) with Vega-Lite
// plots (vega-embed) and plain DOM for tables and the image viewer.
//
// Every plot goes into a <div class="vega-plot" data-plot="NAME">; when all
// have rendered, <body> gets data-plots="rendered" and data-plot-count (the
// report's browser test waits for it and checks each plot's marks).
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('hsmap-data').textContent);
  const main = document.getElementById('sections');
  const contents = document.getElementById('contents');
  const renders = [];
  const palette = ['#1f6fb2', '#d1495b', '#2a9d8f', '#e9a23b', '#7b4fa0', '#5c6b73'];

  // ---- small DOM helpers ----------------------------------------------------
  function el(tag, attributes, ...children) {
    const node = document.createElement(tag);
    for (const [name, value] of Object.entries(attributes || {})) {
      if (value !== undefined && value !== null) node.setAttribute(name, value);
    }
    for (const child of children) {
      if (child === null || child === undefined) continue;
      node.append(child instanceof Node ? child : document.createTextNode(String(child)));
    }
    return node;
  }
  function section(id, title) {
    const node = el('section', {id: id}, el('h2', {}, title));
    main.append(node);
    contents.append(el('a', {href: '#' + id}, title));
    return node;
  }
  function caption(text) { return el('p', {class: 'caption'}, text); }
  function missing(text) { return el('p', {class: 'missing'}, text); }
  function fixed(value, digits) {
    return value === null || value === undefined || !isFinite(value) ? '–' : Number(value).toFixed(digits);
  }
  function significant(value, digits) {
    return value === null || value === undefined || !isFinite(value) ? '–' : Number(value).toPrecision(digits);
  }
  function table(header, rows, numeric) {
    const head = el('tr', {}, ...header.map((h) => el('th', {}, h)));
    const body = rows.map((row) => el('tr', {}, ...row.map((cell, i) =>
      el('td', numeric && numeric[i] ? {class: 'number'} : {}, cell))));
    return el('table', {}, el('thead', {}, head), el('tbody', {}, ...body));
  }

  // A Vega-Lite plot named `name`, rendered as SVG into a new div of `parent`.
  function plot(parent, name, spec) {
    const div = el('div', {class: 'vega-plot', 'data-plot': name});
    parent.append(div);
    const full = Object.assign({$schema: 'https://vega.github.io/schema/vega-lite/v6.json',
                                config: {font: 'system-ui, sans-serif', view: {stroke: '#d9dee6'}}}, spec);
    const done = vegaEmbed(div, full, {actions: false, renderer: 'svg'});
    renders.push(done);
    return done;
  }

  // ---- the run ----------------------------------------------------------------
  document.getElementById('title').textContent = document.title;
  document.getElementById('run-line').textContent =
    'run ' + data.run_folder + ' · survey ' + data.survey_folder + ' · variant ' + data.variant +
    ' · hsmap ' + (data.program_version || '?') + ' · started ' + (data.started_utc || '?') +
    (data.run_complete ? '' : ' · the run did not finish');

  function runSection() {
    const s = section('run', 'Run: stages, time and memory');
    if (data.stages.length) {
      const row = el('div', {class: 'row'});
      s.append(row);
      const stages = data.stages.map((st, i) => Object.assign({order: i}, st));
      const common = {data: {values: stages}, width: 380, height: {step: 22}};
      plot(row, 'stage-times', Object.assign({}, common, {
        title: 'Wall time per stage (s)',
        mark: {type: 'bar', color: palette[0]},
        encoding: {
          y: {field: 'name', type: 'nominal', sort: {field: 'order'}, title: null},
          x: {field: 'time_s', type: 'quantitative', title: 'seconds'},
          tooltip: [{field: 'name'}, {field: 'time_s', format: '.2f', title: 's'}]}}));
      plot(row, 'stage-memory', Object.assign({}, common, {
        title: 'Peak memory when the stage ended (MiB)',
        mark: {type: 'bar', color: palette[2]},
        encoding: {
          y: {field: 'name', type: 'nominal', sort: {field: 'order'}, title: null},
          x: {field: 'peak_rss_mb', type: 'quantitative', title: 'MiB'},
          tooltip: [{field: 'name'}, {field: 'peak_rss_mb', format: '.0f', title: 'MiB'}]}}));
      s.append(caption('Total ' + fixed(data.total_time_s, 1) + ' s, peak memory ' + fixed(data.peak_rss_mb, 0) +
                       ' MiB. A stage skipped because it was up to date shows the time and memory of the run that made it.'));
    } else {
      s.append(missing('No stage has finished in this run folder.'));
    }
    if (data.options.length) {
      s.append(el('h3', {}, 'Options'));
      s.append(table(['option', 'value'], data.options.map((o) => [o.name, o.value])));
    }
    s.append(el('h3', {}, 'Warnings (' + data.warnings.length + ')'));
    s.append(data.warnings.length ? el('ul', {class: 'warnings'}, ...data.warnings.map((w) => el('li', {}, w)))
                                  : missing('No warning.'));
    if (data.notes.length) {
      s.append(el('h3', {}, 'Not shown in this report'));
      s.append(el('ul', {class: 'notes'}, ...data.notes.map((n) => el('li', {}, n))));
    }
  }

  // ---- the trajectory -----------------------------------------------------------
  function trajectorySection() {
    const s = section('trajectory', 'Trajectory');
    if (!data.frames.length) {
      s.append(missing('No trajectory (trajectory/frames.csv) in this run folder.'));
      return;
    }
    const points = [];
    for (const f of data.frames) points.push({kind: 'frame', t: f.t, north: f.north, east: f.east, order: f.frame});
    for (const k of data.keyframes) points.push({kind: 'keyframe', t: k.t, north: k.north, east: k.east});
    for (const x of data.ins_fixes) {
      points.push({kind: x.rejected ? 'INS fix left out' : 'INS fix', t: x.t, north: x.north, east: x.east,
                   ins_line: x.ins_line, rejected_at: x.rejected_at});
    }
    for (const loss of data.losses) {
      for (const frame of [loss.first_frame, loss.last_frame]) {
        const f = data.frames[frame];
        if (f) points.push({kind: 'tracking loss', t: f.t, north: f.north, east: f.east, reason: loss.reason, frame: frame});
      }
    }
    // Equal scales in north and east: the domains are padded to the plot's shape.
    let north = [Infinity, -Infinity], east = [Infinity, -Infinity];
    for (const p of points) {
      north = [Math.min(north[0], p.north), Math.max(north[1], p.north)];
      east = [Math.min(east[0], p.east), Math.max(east[1], p.east)];
    }
    const top = data.mesh_top_view;
    if (top) {
      const rows = top.image.full_height, columns = top.image.full_width;
      north = [Math.min(north[0], top.north_max - rows * top.pixel_m), Math.max(north[1], top.north_max)];
      east = [Math.min(east[0], top.east_min), Math.max(east[1], top.east_min + columns * top.pixel_m)];
    }
    const span = Math.max(north[1] - north[0], east[1] - east[0], 0.01) * 1.06;
    const width = 620, height = Math.max(260, Math.min(760, width * (north[1] - north[0] + 0.06 * span) / (east[1] - east[0] + 0.06 * span)));
    const metres_per_px = Math.max((east[1] - east[0]) * 1.06 / width, (north[1] - north[0]) * 1.06 / height, 1e-6);
    const cn = (north[0] + north[1]) / 2, ce = (east[0] + east[1]) / 2;
    const northDomain = [cn - metres_per_px * height / 2, cn + metres_per_px * height / 2];
    const eastDomain = [ce - metres_per_px * width / 2, ce + metres_per_px * width / 2];
    const x = {field: 'east', type: 'quantitative', title: 'east in W (m)', scale: {domain: eastDomain, nice: false, zero: false}};
    const y = {field: 'north', type: 'quantitative', title: 'north in W (m)', scale: {domain: northDomain, nice: false, zero: false}};
    const kinds = ['frame', 'keyframe', 'INS fix', 'INS fix left out', 'tracking loss'];
    const colours = ['#1f6fb2', '#2a9d8f', '#e9a23b', '#d1495b', '#7b4fa0'];
    const layers = [];
    if (top) {
      layers.push({
        data: {values: [{uri: top.image.uri, e0: top.east_min, e1: top.east_min + top.image.full_width * top.pixel_m,
                         n0: top.north_max - top.image.full_height * top.pixel_m, n1: top.north_max}]},
        mark: {type: 'image', aspect: false, opacity: 0.85},
        encoding: {url: {field: 'uri', type: 'nominal'},
                   x: {field: 'e0', type: 'quantitative', scale: x.scale}, x2: {field: 'e1'},
                   y: {field: 'n1', type: 'quantitative', scale: y.scale}, y2: {field: 'n0'}}});
    }
    layers.push({
      transform: [{filter: "datum.kind == 'frame'"}],
      mark: {type: 'line', strokeWidth: 2},
      encoding: {x: x, y: y, order: {field: 'order', type: 'quantitative'},
                 color: {field: 'kind', type: 'nominal', scale: {domain: kinds, range: colours}, title: null}}});
    layers.push({
      transform: [{filter: "datum.kind != 'frame'"}],
      mark: {type: 'point', filled: true, size: 46, opacity: 0.95},
      encoding: {x: x, y: y,
                 color: {field: 'kind', type: 'nominal', scale: {domain: kinds, range: colours}, title: null},
                 shape: {field: 'kind', type: 'nominal', title: null,
                         scale: {domain: kinds, range: ['circle', 'diamond', 'circle', 'cross', 'triangle-up']}},
                 tooltip: [{field: 'kind'}, {field: 't', format: '.3f'}, {field: 'north', format: '.3f'},
                           {field: 'east', format: '.3f'}, {field: 'ins_line', title: 'ins.csv line'},
                           {field: 'rejected_at', title: 'left out at'}, {field: 'reason'}]}});
    const rejected = data.ins_fixes.filter((f) => f.rejected).length;
    plot(s, 'plan-view', {
      title: 'Plan view' + (top ? ' over the mesh seen from above' : ''),
      width: width, height: Math.round(height), data: {values: points}, layer: layers});
    s.append(caption(data.frames.length + ' frames, ' + data.keyframes.length + ' keyframes, ' +
                     data.ins_fixes.length + ' INS fixes (' + rejected + ' left out by geo-referencing, red crosses), ' +
                     data.losses.length + ' tracking losses (purple triangles at their first and last frame). ' +
                     'W is the local north-east-down frame at the survey\'s origin; the INS fixes are the body\'s position, ' +
                     'the trajectory the RGB camera\'s.'));

    // Depth and altitude against time.
    const t0 = data.frames[0].t;
    const profile = [];
    for (const f of data.frames) {
      profile.push({series: 'camera', t: f.t - t0, down: f.down});
      if (f.seabed_down !== null) profile.push({series: 'seabed under the camera (mesh)', t: f.t - t0, down: f.seabed_down});
    }
    const fixes = data.ins_fixes.map((f) => ({series: f.rejected ? 'INS fix left out' : 'INS fix (body)', t: f.t - t0, down: f.down}))
      .filter((f) => f.t >= -1 && f.t <= data.frames[data.frames.length - 1].t - t0 + 1);
    const lossBands = data.losses.filter((l) => l.t_first !== null && l.t_last !== null)
      .map((l) => ({t0: l.t_first - t0, t1: l.t_last - t0, reason: l.reason}));
    const seriesDomain = ['camera', 'seabed under the camera (mesh)', 'INS fix (body)', 'INS fix left out'];
    const seriesColour = {field: 'series', type: 'nominal', title: null,
                          scale: {domain: seriesDomain, range: ['#1f6fb2', '#6b4f2a', '#e9a23b', '#d1495b']}};
    const profileLayers = [];
    if (lossBands.length) {
      profileLayers.push({data: {values: lossBands}, mark: {type: 'rect', color: '#7b4fa0', opacity: 0.18},
                          encoding: {x: {field: 't0', type: 'quantitative'}, x2: {field: 't1'},
                                     tooltip: [{field: 'reason', title: 'tracking loss'}]}});
    }
    profileLayers.push({data: {values: profile}, mark: {type: 'line', strokeWidth: 2},
                        encoding: {x: {field: 't', type: 'quantitative', title: 'time since the first frame (s)'},
                                   y: {field: 'down', type: 'quantitative', title: 'down in W (m)', scale: {reverse: true, zero: false}},
                                   color: seriesColour}});
    if (fixes.length) {
      profileLayers.push({data: {values: fixes}, mark: {type: 'point', filled: true, size: 30},
                          encoding: {x: {field: 't', type: 'quantitative'}, y: {field: 'down', type: 'quantitative'},
                                     color: seriesColour}});
    }
    const row = el('div', {class: 'row'});
    s.append(row);
    plot(row, 'depth-profile', {title: 'Depth profile', width: 520, height: 240, layer: profileLayers});
    const altitude = data.frames.filter((f) => f.seabed_down !== null)
      .map((f) => ({t: f.t - t0, altitude: f.seabed_down - f.down}));
    if (altitude.length) {
      plot(row, 'altitude-profile', {
        title: 'Altitude of the camera above the mesh', width: 420, height: 240, data: {values: altitude},
        mark: {type: 'line', color: '#2a9d8f', strokeWidth: 2},
        encoding: {x: {field: 't', type: 'quantitative', title: 'time since the first frame (s)'},
                   y: {field: 'altitude', type: 'quantitative', title: 'altitude (m)', scale: {zero: false}}}});
    }
    s.append(caption('Depth is W\'s down axis (metres below the origin\'s depth). The seabed under the camera is the ' +
                     'mesh\'s topmost surface below each frame\'s centre; shaded bands are tracking losses.'));
  }

  // ---- residuals --------------------------------------------------------------
  function residualSection() {
    const s = section('residuals', 'Residuals');
    if (!data.histograms.length) {
      s.append(missing('No residual could be computed from this run folder (see "Not shown in this report").'));
    }
    const row = el('div', {class: 'row'});
    s.append(row);
    data.histograms.forEach((h, index) => {
      // Kept below, outliers stacked on top, each bar a rect from y to y2.
      const bars = [];
      h.counts.forEach((count, i) => {
        const outliers = h.outlier_counts[i];
        const start = i * h.bin_width, end = (i + 1) * h.bin_width;
        if (count - outliers > 0) bars.push({start: start, end: end, low: 0, high: count - outliers, count: count - outliers, kind: 'kept'});
        if (outliers > 0) bars.push({start: start, end: end, low: count - outliers, high: count, count: outliers, kind: 'outlier'});
      });
      if (!bars.length) bars.push({start: 0, end: h.bin_width, low: 0, high: 0, count: 0, kind: 'kept'});
      const layers = [{
        data: {values: bars}, mark: {type: 'rect', stroke: '#ffffff', strokeWidth: 0.5},
        encoding: {x: {field: 'start', type: 'quantitative', title: h.unit, scale: {domain: [0, h.counts.length * h.bin_width], nice: false}},
                   x2: {field: 'end'},
                   y: {field: 'low', type: 'quantitative', title: 'count'}, y2: {field: 'high'},
                   color: {field: 'kind', type: 'nominal', title: null,
                           scale: {domain: ['kept', 'outlier'], range: ['#1f6fb2', '#d1495b']}},
                   tooltip: [{field: 'start', format: '.3g'}, {field: 'end', format: '.3g'}, {field: 'count'}, {field: 'kind'}]}}];
      if (h.outlier_threshold !== null) {
        layers.push({data: {values: [{threshold: h.outlier_threshold}]}, mark: {type: 'rule', color: '#d1495b', strokeDash: [4, 3]},
                     encoding: {x: {field: 'threshold', type: 'quantitative'}}});
      }
      const box = el('div', {});
      row.append(box);
      plot(box, 'histogram-' + index, {title: {text: h.name, fontSize: 12}, width: 400, height: 170, layer: layers});
      box.append(el('p', {class: 'caption', style: 'max-width: 460px'},
        h.total + ' values, median ' + significant(h.median, 3) + ' ' + h.unit + ', RMS ' + significant(h.rms, 3) + ' ' +
        h.unit + '; ' + h.outliers + ' outliers (red: ' + h.outlier_meaning + ')' +
        (h.beyond ? '; ' + h.beyond + ' beyond the plot\'s range (' + h.beyond_outliers + ' of them outliers)' : '') + '.'));
    });
    s.append(caption('Reprojection errors are recomputed from the maps the stages wrote (landmarks projected into the ' +
                     'keyframes that observe them, through survey.yaml\'s camera); INS residuals are each fix against the ' +
                     'body\'s position on the run\'s trajectory at the fix\'s time. The refine and joint stages do not write ' +
                     'their tie points to the run folder, so tie points have no histogram (their counts are in refine/summary.txt).'));
  }

  // ---- calibration ---------------------------------------------------------------
  function calibrationSection() {
    const s = section('calibration', 'Calibration');
    const c = data.calibration;
    if (!c) {
      s.append(missing('No calibration.yaml in this run folder.'));
      return;
    }
    const rows = [];
    const axes = ['x', 'y', 'z'];
    const q = c.rotation_wxyz;
    // The rotation as a vector (axis x angle, degrees), the form the 1-sigma are stated in.
    const half = Math.acos(Math.min(1, Math.abs(q[0])));
    const sign = q[0] < 0 ? -1 : 1;
    const norm = Math.hypot(q[1], q[2], q[3]);
    const rotvec = [q[1], q[2], q[3]].map((v) => norm > 0 ? sign * v / norm * 2 * half * 180 / Math.PI : 0);
    axes.forEach((a, i) => rows.push(['rotation about U\'s ' + a + ' (deg, rotation vector)', fixed(rotvec[i], 4),
      c.sigma_rotation_deg ? '± ' + significant(c.sigma_rotation_deg[i], 3) : 'not estimated']));
    axes.forEach((a, i) => rows.push(['translation along C\'s ' + a + ' (m)', fixed(c.translation_m[i], 4),
      c.sigma_translation_m ? '± ' + significant(c.sigma_translation_m[i], 3) : 'not estimated']));
    rows.push(['time offset d (s)', significant(c.time_offset_s, 4),
               c.time_offset_sigma_s !== null ? '± ' + significant(c.time_offset_sigma_s, 3) : 'not estimated']);
    s.append(table(['T_C_U and d (' + c.variant + ')', 'estimate', '1-sigma'], rows, [false, true, true]));
    s.append(caption('T_C_U places the UHI frame U in the RGB camera frame C; the quaternion (w, x, y, z) is [' +
                     q.map((v) => fixed(v, 6)).join(', ') + ']. From ' + c.source + '.'));
    // The cameras whose intrinsics the run estimated (none listed: survey.yaml's were used as they are).
    for (const camera of c.cameras || []) {
      const cameraRows = camera.parameters.map((p) => {
        const unit = p.unit ? ' (' + p.unit + ')' : '';
        const digits = p.unit ? 6 : 4;
        let change;
        if (p.survey === null) change = 'survey.yaml not read';
        else if (p.change === null) change = 'as survey.yaml';
        else change = (p.change > 0 ? '+' : '') + significant(p.change, 3) + ' (survey.yaml: ' + significant(p.survey, digits) + ')';
        return [p.name + unit, significant(p.estimate, digits),
                p.sigma > 0 ? '± ' + significant(p.sigma, 3) : 'held at survey.yaml\'s', change];
      });
      s.append(el('h3', {}, camera.name));
      const cameraTable = table(['intrinsic', 'estimate', '1-sigma', 'change from survey.yaml'], cameraRows,
                                [false, true, true, true]);
      cameraTable.dataset.camera = camera.key;
      s.append(cameraTable);
    }
    s.append(el('h3', {}, 'Observability and other warnings (' + c.warnings.length + ')'));
    s.append(c.warnings.length ? el('ul', {class: 'warnings'}, ...c.warnings.map((w) => el('li', {}, w)))
                               : missing('None: every component was determined.'));
  }

  // ---- ortho-images: side by side, swipe, blink; spectra --------------------------
  function orthoSection() {
    const s = section('ortho', 'Ortho-images and spectra');
    const hs = data.hyperspectral_ortho, rgb = data.rgb_ortho;
    if (!hs && !rgb) {
      s.append(missing('No ortho-image in this run folder.'));
      return;
    }
    const images = [];
    if (hs) images.push({label: 'hyperspectral (quick-look)', image: hs, hyperspectral: true});
    if (rgb) images.push({label: 'RGB ortho-image of the mesh', image: rgb, hyperspectral: false});
    const base = images[0].image;
    const view = {scale: 1, x: 0, y: 0, mode: 'side', swipe: 0.5, blinkShown: 0, timer: null};
    const tools = el('div', {class: 'viewer-tools'});
    const viewports = el('div', {class: 'viewports'});
    s.append(tools, viewports);
    const available = Math.min(1400, s.clientWidth || 1200);
    let boxWidth, boxHeight;
    const panes = [];

    function layout() {
      viewports.textContent = '';
      panes.length = 0;
      const count = view.mode === 'side' && images.length > 1 ? 2 : 1;
      boxWidth = Math.floor((available - 10 * (count - 1)) / count);
      boxHeight = Math.min(620, Math.round(boxWidth * base.height / base.width));
      const fit = Math.min(boxWidth / base.width, boxHeight / base.height);
      if (!view.fitted) { view.scale = fit; view.x = (boxWidth - base.width * fit) / 2; view.y = (boxHeight - base.height * fit) / 2; view.fitted = true; }
      const groups = view.mode === 'side' ? images.map((i) => [i]) : [images];
      for (const group of groups) {
        const pane = el('div', {class: 'viewport', style: 'width:' + boxWidth + 'px;height:' + boxHeight + 'px'});
        const imgs = group.map((item) => {
          const img = el('img', {src: item.image.uri, width: item.image.width, height: item.image.height, alt: item.label,
                                 draggable: 'false'});
          img.dataset.hyperspectral = item.hyperspectral ? '1' : '0';
          pane.append(img);
          return img;
        });
        const label = el('div', {class: 'label'}, group.map((g) => g.label).join(' / '));
        pane.append(label);
        let line = null;
        if (view.mode === 'swipe' && group.length > 1) {
          line = el('div', {class: 'swipe-line'});
          pane.append(line);
        }
        viewports.append(pane);
        panes.push({pane: pane, imgs: imgs, group: group, line: line, label: label});
        attach(pane);
      }
      draw();
    }

    function draw() {
      for (const p of panes) {
        p.imgs.forEach((img, i) => {
          const item = p.group[i];
          const k = view.scale * base.width / item.image.width;
          img.style.transform = 'translate(' + view.x + 'px,' + view.y + 'px) scale(' + k + ')';
          img.style.clipPath = '';
          img.style.visibility = 'visible';
          img.style.zIndex = String(p.imgs.length - i);  // the hyperspectral image over the RGB one
          if (view.mode === 'swipe' && i === 0 && p.imgs.length > 1) {
            // The first image (hyperspectral) shows left of the swipe line.
            const cut = (view.swipe * boxWidth - view.x) / (base.width * view.scale);
            img.style.clipPath = 'inset(0 ' + Math.max(0, 100 - cut * 100) + '% 0 0)';
          }
          if (view.mode === 'blink' && p.imgs.length > 1) img.style.visibility = i === view.blinkShown ? 'visible' : 'hidden';
        });
        if (p.line) p.line.style.left = Math.round(view.swipe * boxWidth) + 'px';
        if (view.mode === 'blink' && p.group.length > 1) p.label.textContent = p.group[view.blinkShown].label;
        p.pane.querySelectorAll('.marker').forEach((m) => m.remove());
        selected.forEach((point, i) => {
          const mx = view.x + (point.column + 0.5) / spectra.image_columns * base.width * view.scale;
          const my = view.y + (point.row + 0.5) / spectra.image_rows * base.height * view.scale;
          p.pane.append(el('div', {class: 'marker', style: 'left:' + mx + 'px;top:' + my + 'px;border-color:' + palette[i % palette.length]}));
        });
      }
    }

    // One drag at a time, whichever pane it started in (listeners on window, attached once).
    let drag = null;
    window.addEventListener('mousemove', (event) => {
      if (!drag) return;
      const dx = event.clientX - drag.x, dy = event.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
      view.x += dx; view.y += dy;
      drag.x = event.clientX; drag.y = event.clientY;
      draw();
    });
    window.addEventListener('mouseup', (event) => {
      if (!drag) return;
      const {pane, moved} = drag;
      drag = null;
      pane.classList.remove('dragging');
      if (!moved && pane.contains(event.target)) {
        const rect = pane.getBoundingClientRect();
        pick(event.clientX - rect.left, event.clientY - rect.top);
      }
    });
    function attach(pane) {
      pane.addEventListener('wheel', (event) => {
        event.preventDefault();
        const rect = pane.getBoundingClientRect();
        zoomAt(event.clientX - rect.left, event.clientY - rect.top, event.deltaY < 0 ? 1.25 : 0.8);
      }, {passive: false});
      pane.addEventListener('mousedown', (event) => {
        event.preventDefault();
        drag = {pane: pane, x: event.clientX, y: event.clientY, moved: false};
        pane.classList.add('dragging');
      });
    }

    function zoomAt(px, py, factor) {
      const scale = Math.min(64, Math.max(0.05, view.scale * factor));
      view.x = px - (px - view.x) * scale / view.scale;
      view.y = py - (py - view.y) * scale / view.scale;
      view.scale = scale;
      draw();
    }

    const modes = [['side', 'Side by side'], ['swipe', 'Swipe'], ['blink', 'Blink']];
    const buttons = {};
    for (const [mode, text] of modes) {
      if (mode !== 'side' && images.length < 2) continue;
      const button = el('button', {type: 'button'}, text);
      button.addEventListener('click', () => setMode(mode));
      buttons[mode] = button;
      tools.append(button);
    }
    const zoomIn = el('button', {type: 'button'}, 'Zoom +'), zoomOut = el('button', {type: 'button'}, 'Zoom −');
    const reset = el('button', {type: 'button'}, 'Fit');
    zoomIn.addEventListener('click', () => zoomAt(boxWidth / 2, boxHeight / 2, 1.5));
    zoomOut.addEventListener('click', () => zoomAt(boxWidth / 2, boxHeight / 2, 1 / 1.5));
    reset.addEventListener('click', () => { view.fitted = false; layout(); });
    const slider = el('input', {type: 'range', min: '0', max: '100', value: '50', title: 'swipe position'});
    slider.addEventListener('input', () => { view.swipe = slider.value / 100; draw(); });
    tools.append(zoomIn, zoomOut, reset, el('span', {class: 'caption'}, 'swipe:'), slider);

    function setMode(mode) {
      view.mode = mode;
      for (const [name, button] of Object.entries(buttons)) button.classList.toggle('on', name === mode);
      slider.disabled = mode !== 'swipe';
      if (view.timer) { clearInterval(view.timer); view.timer = null; }
      if (mode === 'blink') view.timer = setInterval(() => { view.blinkShown = 1 - view.blinkShown; draw(); }, 700);
      view.fitted = false;
      layout();
    }

    s.append(caption('Both ortho-images are north-up on the same grid' +
      (isFinite(data.ortho_pixel_m) && data.ortho_pixel_m ? ' (' + fixed(data.ortho_pixel_m * 1000, 1) + ' mm pixels, ' +
        base.full_width + ' × ' + base.full_height + ' in the products' +
        (base.width !== base.full_width ? ', shown at ' + base.width + ' × ' + base.height : '') + ')' : '') +
      '. Wheel or buttons zoom, drag pans; Swipe shows the hyperspectral image left of the line (move the slider), ' +
      'Blink alternates them. Click on the hyperspectral image to add its spectrum below.'));

    // Spectra at selected points, from the embedded grid.
    const spectra = data.spectra;
    const selected = [];
    const spectrumBox = el('div', {});
    let values = null;
    if (spectra) {
      const bytes = Uint8Array.from(atob(spectra.values_base64), (c) => c.charCodeAt(0));
      values = new DataView(bytes.buffer);
    }
    const bands = spectra ? spectra.wavelengths_nm.length : 0;
    function spectrumAt(column, row) {
      const cell = (Math.floor(row / spectra.block_px) * spectra.columns + Math.floor(column / spectra.block_px)) * bands;
      const out = [];
      for (let b = 0; b < bands; ++b) {
        const q = values.getUint16((cell + b) * 2, true);
        if (q === 65535) return null;
        out.push(spectra.offsets[b] + spectra.scales[b] * q);
      }
      return out;
    }
    function addPoint(column, row) {
      const spectrum = spectrumAt(column, row);
      if (!spectrum) return false;
      selected.push({column: column, row: row, spectrum: spectrum});
      if (selected.length > palette.length) selected.shift();
      return true;
    }
    function pick(px, py) {
      if (!spectra) return;
      const column = Math.floor((px - view.x) / (base.width * view.scale) * spectra.image_columns);
      const row = Math.floor((py - view.y) / (base.height * view.scale) * spectra.image_rows);
      if (column < 0 || row < 0 || column >= spectra.image_columns || row >= spectra.image_rows) return;
      if (addPoint(column, row)) { draw(); drawSpectra(); }
    }
    let spectrumView = null;
    function drawSpectra() {
      const rows = [];
      selected.forEach((point, i) => point.spectrum.forEach((value, b) => rows.push({
        point: 'point ' + (i + 1) + ' (col ' + point.column + ', row ' + point.row + ')', order: i,
        wavelength: spectra.wavelengths_nm[b], value: value})));
      const names = selected.map((point, i) => 'point ' + (i + 1) + ' (col ' + point.column + ', row ' + point.row + ')');
      if (spectrumView) spectrumView.finalize();
      spectrumBox.textContent = '';
      const done = plot(spectrumBox, 'spectra', {
        title: 'Radiance spectra at the selected points', width: 640, height: 260, data: {values: rows},
        mark: {type: 'line', point: true, strokeWidth: 2},
        encoding: {x: {field: 'wavelength', type: 'quantitative', title: 'wavelength (nm)', scale: {zero: false}},
                   y: {field: 'value', type: 'quantitative', title: 'radiance (DN)', scale: {zero: false}},
                   color: {field: 'point', type: 'nominal', title: null, scale: {domain: names, range: palette}},
                   tooltip: [{field: 'point'}, {field: 'wavelength', format: '.1f'}, {field: 'value', format: '.4g'}]}});
      done.then((result) => { spectrumView = result.view; });
    }
    setMode('side');
    s.append(el('h3', {}, 'Spectra'));
    if (spectra) {
      // A first point at the image's centre (or the nearest block with data), so the plot is never empty.
      const cx = Math.floor(spectra.image_columns / 2), cy = Math.floor(spectra.image_rows / 2);
      let found = false;
      for (let r = 0; r < Math.max(spectra.columns, spectra.rows) && !found; ++r) {
        for (let dy = -r; dy <= r && !found; ++dy) {
          for (let dx = -r; dx <= r && !found; ++dx) {
            const column = cx + dx * spectra.block_px, row = cy + dy * spectra.block_px;
            if (column >= 0 && row >= 0 && column < spectra.image_columns && row < spectra.image_rows) found = addPoint(column, row);
          }
        }
      }
      s.append(spectrumBox);
      drawSpectra();
      draw();
      s.append(caption('Each spectrum is the mean over a block of ' + spectra.block_px + ' × ' + spectra.block_px +
                       ' ortho pixels (' + spectra.columns + ' × ' + spectra.rows + ' blocks embedded): ' + spectra.meaning +
                       '. Up to ' + palette.length + ' points; the oldest is dropped.'));
    } else {
      s.append(missing('No hyperspectral ortho-image (hyperspectral/ortho.hdr) to read spectra from.'));
    }
  }

  // ---- the mesh from above ------------------------------------------------------------
  function meshSection() {
    const s = section('mesh', 'Mesh seen from above');
    const top = data.mesh_top_view;
    if (!top) {
      s.append(missing('No mesh (map/mesh.ply) in this run folder.'));
      return;
    }
    s.append(el('div', {class: 'top-view'}, el('img', {src: top.image.uri, width: top.image.width, height: top.image.height,
                                                     alt: 'the mesh seen from above'})));
    s.append(caption('map/mesh.ply seen from straight above, north up, in its vertex colours shaded by a light from the ' +
                     'north-west; ' + fixed(top.image.width * top.pixel_m, 2) + ' m × ' + fixed(top.image.height * top.pixel_m, 2) +
                     ' m, ' + fixed(top.pixel_m * 1000, 1) + ' mm per pixel. The plan view above draws the trajectory over it.'));
  }

  // ---- against the truth -----------------------------------------------------------------
  function truthSection() {
    const s = section('truth', 'Against the truth');
    if (!data.metrics.length) {
      s.append(missing('Not scored: on a simulated survey, `hsmap evaluate RUN --truth SURVEY/truth` writes metrics.json ' +
                       'and refreshes this report with the metrics and the ortho displacement field.'));
      return;
    }
    function unit(name) {
      if (/_deg(\b|$)/.test(name)) return 'deg';
      if (/_m(\b|$)/.test(name)) return 'm';
      if (/timings_s|_s(\b|$)/.test(name)) return 's';
      if (/_mb$/.test(name)) return 'MiB';
      if (/_per_m/.test(name)) return '1/m';
      return '';
    }
    s.append(table(['metric (docs/EVALUATE.md)', 'value', 'unit'],
                   data.metrics.map((m) => [m.name, m.value === null ? 'null (does not apply)' : significant(m.value, 4), unit(m.name)]),
                   [false, true, false]));
    if (!data.ortho_patches.length) {
      s.append(missing('No ortho displacement field (report/ortho_patches.csv).'));
      return;
    }
    const patches = data.ortho_patches;
    let spacing = Infinity, largest = 0;
    for (const a of patches) {
      largest = Math.max(largest, Math.hypot(a.displacement_north, a.displacement_east));
      for (const b of patches) {
        const d = Math.hypot(a.north - b.north, a.east - b.east);
        if (d > 0) spacing = Math.min(spacing, d);
      }
    }
    if (!isFinite(spacing)) spacing = 0.3;
    const k = largest > 0 ? 0.8 * spacing / largest : 1;
    const vectors = patches.map((p) => ({
      north: p.north, east: p.east, north2: p.north + k * p.displacement_north, east2: p.east + k * p.displacement_east,
      magnitude_mm: 1000 * Math.hypot(p.displacement_north, p.displacement_east),
      bearing: Math.atan2(p.displacement_east, p.displacement_north) * 180 / Math.PI, response: p.response}));
    const colour = {field: 'magnitude_mm', type: 'quantitative', title: 'mm', scale: {scheme: 'viridis'}};
    const tooltip = [{field: 'north', format: '.2f'}, {field: 'east', format: '.2f'},
                     {field: 'magnitude_mm', format: '.1f', title: 'displacement (mm)'}, {field: 'response', format: '.2f'}];
    plot(s, 'ortho-displacements', {
      title: 'Ortho-image displacement against the truth (arrows × ' + significant(k, 2) + ')',
      width: 520, height: 420, data: {values: vectors},
      layer: [
        {mark: {type: 'rule', strokeWidth: 2},
         encoding: {x: {field: 'east', type: 'quantitative', title: 'east (m)', scale: {zero: false}},
                    y: {field: 'north', type: 'quantitative', title: 'north (m)', scale: {zero: false}},
                    x2: {field: 'east2'}, y2: {field: 'north2'}, color: colour, tooltip: tooltip}},
        {mark: {type: 'point', shape: 'triangle-up', filled: true, size: 60},
         encoding: {x: {field: 'east2', type: 'quantitative'}, y: {field: 'north2', type: 'quantitative'},
                    angle: {field: 'bearing', type: 'quantitative', scale: {domain: [-180, 180], range: [-180, 180]}},
                    color: colour, tooltip: tooltip}},
        {mark: {type: 'point', filled: true, size: 14, color: '#333'},
         encoding: {x: {field: 'east', type: 'quantitative'}, y: {field: 'north', type: 'quantitative'}}}]});
    s.append(caption(patches.length + ' patches of the produced ortho-image matched to the true one by phase correlation ' +
                     '(report/ortho_patches.csv): each arrow goes from the patch\'s centre along its displacement, ' +
                     'lengthened ' + significant(k, 2) + ' times so it can be seen; largest ' + fixed(largest * 1000, 1) + ' mm.'));
  }

  const builders = [runSection, trajectorySection, residualSection, calibrationSection, orthoSection, meshSection, truthSection];
  for (const build of builders) {
    try {
      build();
    } catch (error) {
      console.error('hsmap report: ' + build.name + ' failed: ' + (error && error.stack || error));
    }
  }
  document.body.dataset.plotsExpected = String(document.querySelectorAll('.vega-plot').length);
  Promise.all(renders).then(() => {
    document.body.dataset.plotCount = String(renders.length);
    document.body.dataset.plots = 'rendered';
  }, (error) => {
    console.error('hsmap report: a plot failed to render: ' + error);
    document.body.dataset.plots = 'failed';
  });
})();
