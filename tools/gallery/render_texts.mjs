#!/usr/bin/env node
// The texts as pages: every lesson text, exercise README and document of the
// source tree rendered to HTML under OUT/pages/, with its maths (KaTeX, on
// the server: the pages need no script), its figures and working links.
//
//   node tools/gallery/render_texts.mjs --source DIR --out OUT [--pages NAME]
//
// (--pages: the folder inside OUT to write, `pages` by default; the main job
// writes a fresh folder beside it and swaps the two, so a text removed from
// the tree leaves no page behind, and a failed run leaves the last pages.)
// What is rendered: README.md, CONTRIBUTING.md, lessons/*/README.md,
// exercises/*/README.md, docs/*.md, slides/README.md, and every Markdown file
// of the tree they link to; each X.md becomes OUT/pages/X.html.
//
// Links, as a student reading the page needs them:
//   - to a rendered text: its page (anchors kept; headings carry GitHub's ids);
//   - to a deck (slides/NN_topic.md): the built deck, OUT/slides/NN_topic.html;
//   - to a source file (lib/, tests/, exercises/*.cpp, tools/…): a page of
//     the file with its lines numbered and highlighted, OUT/pages/X.cpp.html;
//   - to a folder, or another file of the tree (a mesh, a scene): the file;
//   - an image of lessons/NN_topic/figures/: the drawing of the run in
//     OUT/lessonNN/ (OUT/lab/ for a lab_*.png) when there is one, the kept
//     copy otherwise, so a timing plot shows the run its tables come from;
//   - a web address: unchanged.
// Maths: $…$ inline and $$…$$ displayed (a paragraph of its own, or inside
// one), as GitHub reads them; KaTeX renders them at build time, and its
// stylesheet and fonts are copied to OUT/pages/assets/.
//
// Prints one line per page; exit code 1 (after writing every page) when a
// formula did not render or a link names nothing, 2 when the tools are missing.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';

const require = createRequire(import.meta.url);
const HERE = path.dirname(fileURLToPath(import.meta.url));

function load(name) {
  try {
    return require(name);
  } catch (e) {
    console.error(`render_texts: cannot load ${name}: run tools/install-deps (npm ci) (${e.message})`);
    process.exit(2);
  }
}
const MarkdownIt = load('markdown-it');
const katex = load('katex');
const hljs = load('highlight.js');

const SEED_GLOBS = [
  ['', /^(README|CONTRIBUTING)\.md$/],
  ['lessons', /^\d\d_[\w-]+$/, 'README.md'],
  ['exercises', /^\d\d_[\w-]+$/, 'README.md'],
  ['docs', /\.md$/],
  ['slides', /^README\.md$/],
];
const CODE_LANGUAGES = {
  '.cpp': 'cpp', '.hpp': 'cpp', '.h': 'cpp', '.cc': 'cpp', '.py': 'python', '.mjs': 'javascript',
  '.js': 'javascript', '.cjs': 'javascript', '.cmake': 'cmake', '.json': 'json', '.sh': 'bash',
  '.css': 'css', '.html': 'xml', '.txt': 'plaintext', '.toml': 'ini', '.yml': 'yaml', '.yaml': 'yaml',
};
const SHELL_NAMES = new Set(['grade', 'bootstrap', 'install-deps', 'format', 'fuzz', 'run']);

function parseArgs(argv) {
  const options = { source: null, out: null, pages: 'pages' };
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--source') options.source = argv[++i];
    else if (argv[i] === '--out') options.out = argv[++i];
    else if (argv[i] === '--pages') options.pages = argv[++i];
    else if (argv[i] === '-h' || argv[i] === '--help') {
      console.log('usage: node tools/gallery/render_texts.mjs --source DIR --out OUT');
      process.exit(0);
    } else {
      console.error(`render_texts: unknown argument ${argv[i]}`);
      process.exit(2);
    }
  }
  if (!options.source || !options.out) {
    console.error('render_texts: --source and --out are needed');
    process.exit(2);
  }
  if (!/^[\w.-]+$/.test(options.pages)) {
    console.error('render_texts: --pages names one folder inside OUT');
    process.exit(2);
  }
  return { source: path.resolve(options.source), out: path.resolve(options.out), pages: options.pages };
}

// --- heading ids, as GitHub makes them (tools/gallery/text_links.py: slug) ------------

function slug(text) {
  const plain = text
    .replace(/!\[[^\]]*\]\([^)]*\)/g, '')
    .replace(/\[([^\]]*)\]\([^)]*\)/g, '$1')
    .replace(/<[^>]+>/g, '')
    .replace(/`/g, '')
    .toLowerCase()
    .trim();
  let out = '';
  for (const c of plain) {
    if (c === ' ') out += '-';
    else if (c === '-' || c === '_' || /[\p{L}\p{N}\p{Mn}]/u.test(c)) out += c;
  }
  return out;
}

// --- maths: $…$ and $$…$$ ----------------------------------------------------------------

const mathErrors = [];

function renderMath(tex, display, where) {
  try {
    return katex.renderToString(tex, { displayMode: display, throwOnError: true, output: 'html', strict: 'ignore' });
  } catch (e) {
    mathErrors.push(`${where}: ${e.message.split('\n')[0]}: ${tex.slice(0, 80)}`);
    return katex.renderToString(tex, { displayMode: display, throwOnError: false, output: 'html', strict: 'ignore' });
  }
}

function mathPlugin(md) {
  // $$ … $$ starting a line: a display of one or several lines.
  md.block.ruler.before('paragraph', 'math_block', (state, startLine, endLine, silent) => {
    const start = state.bMarks[startLine] + state.tShift[startLine];
    const max = state.eMarks[startLine];
    if (state.sCount[startLine] - state.blkIndent >= 4) return false;
    if (state.src.slice(start, start + 2) !== '$$') return false;
    let content = state.src.slice(start + 2, max);
    let line = startLine;
    let closed = false;
    const first = content.trimEnd();
    if (first.endsWith('$$') && first.length >= 2) {
      content = first.slice(0, -2);
      closed = true;
    }
    while (!closed) {
      line += 1;
      if (line >= endLine) return false;
      const s = state.bMarks[line] + state.tShift[line];
      const text = state.src.slice(s, state.eMarks[line]).trimEnd();
      if (text.endsWith('$$')) {
        content += '\n' + text.slice(0, -2);
        closed = true;
      } else {
        content += '\n' + text;
      }
    }
    if (silent) return true;
    const token = state.push('math_block', 'math', 0);
    token.block = true;
    token.content = content.trim();
    token.map = [startLine, line + 1];
    state.line = line + 1;
    return true;
  }, { alt: ['paragraph', 'reference', 'blockquote', 'list'] });

  // $…$ and $$…$$ inside a line. A single $ opens when a non-space follows and
  // closes when a non-space precedes it and no digit follows (GitHub's rule).
  md.inline.ruler.after('escape', 'math_inline', (state, silent) => {
    const src = state.src;
    const pos = state.pos;
    if (src[pos] !== '$') return false;
    const display = src[pos + 1] === '$';
    const open = display ? 2 : 1;
    if (!display && (pos + 1 >= src.length || /\s/.test(src[pos + 1]))) return false;
    let end = pos + open;
    for (;;) {
      end = src.indexOf(display ? '$$' : '$', end);
      if (end < 0) return false;
      if (src[end - 1] === '\\') {
        end += 1;
        continue;
      }
      if (!display && (/\s/.test(src[end - 1]) || /\d/.test(src[end + 1] || ''))) {
        end += 1;
        continue;
      }
      break;
    }
    const content = src.slice(pos + open, end);
    if (!content.trim()) return false;
    if (!silent) {
      const token = state.push('math_inline', 'math', 0);
      token.content = content;
      token.markup = display ? '$$' : '$';
    }
    state.pos = end + open;
    return true;
  });

  md.renderer.rules.math_block = (tokens, i, _options, env) =>
    `<div class="math">${renderMath(tokens[i].content, true, `${env.rel}:${tokens[i].map[0] + 1}`)}</div>\n`;
  md.renderer.rules.math_inline = (tokens, i, _options, env) =>
    renderMath(tokens[i].content, tokens[i].markup === '$$', env.rel);
}

// --- headings: GitHub's ids ------------------------------------------------------------

function headingIds(md) {
  md.core.ruler.push('heading_ids', (state) => {
    const seen = new Map();
    const tokens = state.tokens;
    for (let i = 0; i < tokens.length; ++i) {
      if (tokens[i].type !== 'heading_open') continue;
      const inline = tokens[i + 1];
      const text = inline.children.filter((t) => t.type === 'text' || t.type === 'code_inline')
        .map((t) => t.content).join('');
      const base = slug(text);
      const n = seen.get(base) || 0;
      seen.set(base, n + 1);
      tokens[i].attrSet('id', n === 0 ? base : `${base}-${n}`);
    }
  });
}

// --- the pages ---------------------------------------------------------------------------

function escapeHtml(text) {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
}

function highlight(code, language) {
  if (language && hljs.getLanguage(language)) {
    try {
      return hljs.highlight(code, { language, ignoreIllegals: true }).value;
    } catch (_) { /* fall through */ }
  }
  return escapeHtml(code);
}

function makeMarkdown() {
  const md = new MarkdownIt({
    html: true,
    linkify: false,
    typographer: false,
    highlight: (code, lang) => highlight(code, { sh: 'bash', shell: 'bash', console: 'bash' }[lang] || lang),
  });
  md.use(mathPlugin);
  md.use(headingIds);
  return md;
}

function seedTexts(source) {
  const found = [];
  for (const [folder, pattern, file] of SEED_GLOBS) {
    const dir = path.join(source, folder);
    if (!fs.existsSync(dir)) continue;
    for (const name of fs.readdirSync(dir).sort()) {
      if (!pattern.test(name)) continue;
      const candidate = file ? path.join(dir, name, file) : path.join(dir, name);
      if (fs.existsSync(candidate) && fs.statSync(candidate).isFile()) found.push(candidate);
    }
  }
  return found;
}

function isInside(child, parent) {
  const rel = path.relative(parent, child);
  return rel === '' || (!rel.startsWith('..') && !path.isAbsolute(rel));
}

function relUrl(fromDir, target) {
  const rel = path.relative(fromDir, target).split(path.sep).map(encodeURIComponent).join('/');
  return rel || '.';
}

class Site {
  constructor(source, out, pages) {
    this.source = source;
    this.out = out;
    this.pages = path.join(out, pages);
    this.texts = new Set();      // absolute .md paths rendered
    this.codeFiles = new Set();  // absolute source files given a page
    this.problems = [];
  }

  pageOf(file) {
    const rel = path.relative(this.source, file);
    return path.join(this.pages, rel.replace(/\.md$/, '') + (file.endsWith('.md') ? '.html' : '.html'));
  }

  codePageOf(file) {
    return path.join(this.pages, path.relative(this.source, file) + '.html');
  }

  isCode(file) {
    const ext = path.extname(file);
    if (CODE_LANGUAGES[ext]) return true;
    return ext === '' && (path.basename(file) === 'CMakeLists.txt' || SHELL_NAMES.has(path.basename(file)));
  }

  // Where a link of the text `from` (absolute .md path) should point, from the page `pageDir`.
  resolve(from, target, pageDir, image) {
    if (/^[a-z][a-z0-9+.-]*:/i.test(target) || target.startsWith('//')) return target;
    const hash = target.indexOf('#');
    const pathPart = hash >= 0 ? target.slice(0, hash) : target;
    const fragment = hash >= 0 ? target.slice(hash) : '';
    if (!pathPart) return target;
    let decoded;
    try {
      decoded = decodeURIComponent(pathPart);
    } catch (_) {
      decoded = pathPart;
    }
    const absolute = path.resolve(path.dirname(from), decoded);
    const sourceOut = path.join(this.source, 'out');
    const rel = path.relative(this.source, from);
    if (isInside(absolute, sourceOut)) {  // a link into the run's output: this run's OUT
      const mapped = path.join(this.out, path.relative(sourceOut, absolute));
      if (!fs.existsSync(mapped)) this.problems.push(`${rel}: '${target}' names ${mapped}, which this run did not write`);
      return relUrl(pageDir, mapped) + fragment;
    }
    if (!isInside(absolute, this.source)) {
      this.problems.push(`${rel}: '${target}' leaves the source tree`);
      return target;
    }
    if (!fs.existsSync(absolute)) {
      this.problems.push(`${rel}: '${target}' names ${path.relative(this.source, absolute)}, which does not exist`);
      return target;
    }
    const figure = path.relative(this.source, absolute).match(/^lessons\/(\d\d)_[^/]+\/figures\/([^/]+\.png)$/);
    if (image && figure) {
      const drawn = figure[2].startsWith('lab_')
        ? path.join(this.out, 'lab', figure[2])
        : path.join(this.out, `lesson${figure[1]}`, figure[2]);
      return relUrl(pageDir, fs.existsSync(drawn) ? drawn : absolute);
    }
    if (fs.statSync(absolute).isDirectory()) return relUrl(pageDir, absolute) + '/';
    const deck = path.relative(this.source, absolute).match(/^slides\/(\d\d_[\w-]+)\.md$/);
    if (deck) {  // a deck: the built deck when the main job built it, its Markdown otherwise
      const built = path.join(this.out, 'slides', `${deck[1]}.html`);
      return relUrl(pageDir, fs.existsSync(built) ? built : absolute) + fragment;
    }
    if (absolute.endsWith('.md')) {
      this.texts.add(absolute);
      return relUrl(pageDir, this.pageOf(absolute)) + fragment;
    }
    if (!image && this.isCode(absolute)) {
      this.codeFiles.add(absolute);
      return relUrl(pageDir, this.codePageOf(absolute)) + fragment;
    }
    return relUrl(pageDir, absolute) + fragment;
  }
}

function rewriteLinks(md, site) {
  md.core.ruler.push('illum_links', (state) => {
    const env = state.env;
    const walk = (tokens) => {
      for (const t of tokens) {
        if (t.type === 'link_open') {
          const href = t.attrGet('href');
          if (href) t.attrSet('href', site.resolve(env.file, href, env.pageDir, false));
        } else if (t.type === 'image') {
          const src = t.attrGet('src');
          if (src) t.attrSet('src', site.resolve(env.file, src, env.pageDir, true));
        } else if ((t.type === 'html_inline' || t.type === 'html_block') && /\b(?:src|href)="/.test(t.content)) {
          t.content = t.content.replace(/\b(src|href)="([^"]+)"/g, (_, attr, value) =>
            `${attr}="${escapeHtml(site.resolve(env.file, value, env.pageDir, attr === 'src'))}"`);
        }
        if (t.children) walk(t.children);
      }
    };
    walk(state.tokens);
  });
}

const CSS = `
:root { --fg:#1d2330; --muted:#5b6475; --line:#dde2ea; --bg:#f6f7f9; --card:#fff; --accent:#1f5fbf; --code:#f3f5f8; }
* { box-sizing: border-box; }
body { margin:0; font:16px/1.6 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif; color:var(--fg); background:var(--bg); }
nav.top { background:var(--card); border-bottom:1px solid var(--line); padding:8px 24px; font-size:14px; }
nav.top a { color:var(--accent); text-decoration:none; margin-right:14px; }
nav.top .path { color:var(--muted); }
main { max-width: 980px; margin: 0 auto; padding: 12px 28px 40px; background:var(--card); border-left:1px solid var(--line); border-right:1px solid var(--line); min-height: 100vh; }
a { color: var(--accent); }
h1 { font-size: 30px; line-height: 1.25; border-bottom: 1px solid var(--line); padding-bottom: 8px; }
h2 { font-size: 23px; border-bottom: 1px solid var(--line); padding-bottom: 4px; margin-top: 34px; }
h3 { font-size: 18px; margin-top: 26px; }
code { font: 13.5px/1.45 ui-monospace,"DejaVu Sans Mono",monospace; background: var(--code); padding: 1px 4px; border-radius: 4px; }
pre { background: var(--code); padding: 12px 14px; border-radius: 6px; overflow-x: auto; }
pre code { background: none; padding: 0; }
img { max-width: 100%; height: auto; }
p img { vertical-align: top; }
table { border-collapse: collapse; font-size: 14px; font-variant-numeric: tabular-nums; display: block; overflow-x: auto; max-width: 100%; }
th, td { border: 1px solid var(--line); padding: 3px 9px; text-align: left; }
th { background: #eef1f5; }
blockquote { margin: 0; padding: 2px 16px; border-left: 4px solid var(--line); color: #3b4252; }
.math { overflow-x: auto; overflow-y: hidden; }
.katex-display { margin: 0.8em 0; }
footer { color: var(--muted); font-size: 13px; margin-top: 40px; border-top: 1px solid var(--line); padding-top: 10px; }
table.code { display: table; border: none; font: 13px/1.45 ui-monospace,"DejaVu Sans Mono",monospace; width: 100%; }
table.code td { border: none; padding: 0 10px; vertical-align: top; white-space: pre; }
table.code td.n { color: var(--muted); text-align: right; user-select: none; width: 1%; }
table.code tr:target { background: #fff6c8; }
`;

function page(site, file, title, body, pageDir, sourceLabel) {
  const assets = relUrl(pageDir, path.join(site.pages, 'assets'));
  const index = relUrl(pageDir, path.join(site.out, 'index.html'));
  const rel = path.relative(site.source, file);
  const sourceLink = relUrl(pageDir, file);
  return `<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>${escapeHtml(title)} — illum</title>
<link rel="stylesheet" href="${assets}/katex/katex.min.css">
<link rel="stylesheet" href="${assets}/highlight.css">
<style>${CSS}</style>
</head>
<body>
<nav class="top"><a href="${index}">illum: lessons and outputs</a><span class="path">${escapeHtml(rel)}</span>
 · <a href="${sourceLink}">${sourceLabel}</a></nav>
<main>
${body}
<footer>Rendered from <code>${escapeHtml(rel)}</code> by <code>tools/gallery/render_texts.mjs</code> (the main job).</footer>
</main>
</body>
</html>
`;
}

function titleOf(markdown, fallback) {
  const m = markdown.match(/^#\s+(.+)$/m);
  return m ? m[1].replace(/[`*_]/g, '').trim() : fallback;
}

function renderText(site, md, file) {
  const markdown = fs.readFileSync(file, 'utf8');
  const target = site.pageOf(file);
  const pageDir = path.dirname(target);
  const env = { file, pageDir, rel: path.relative(site.source, file) };
  const body = md.render(markdown, env);
  return { target, html: page(site, file, titleOf(markdown, env.rel), body, pageDir, 'Markdown source') };
}

function renderCode(site, file) {
  const text = fs.readFileSync(file, 'utf8');
  const target = site.codePageOf(file);
  const pageDir = path.dirname(target);
  const ext = path.extname(file);
  const language = CODE_LANGUAGES[ext] || (path.basename(file) === 'CMakeLists.txt' ? 'cmake' : 'bash');
  const highlighted = highlight(text.replace(/\n$/, ''), language);
  // Highlighted spans may cross lines: close and reopen them at each line's end.
  const rows = [];
  let open = [];
  highlighted.split('\n').forEach((line, i) => {
    const prefix = open.join('');
    const tags = line.match(/<span[^>]*>|<\/span>/g) || [];
    for (const tag of tags) {
      if (tag === '</span>') open.pop();
      else open.push(tag);
    }
    rows.push(`<tr id="L${i + 1}"><td class="n">${i + 1}</td><td>${prefix}${line}${'</span>'.repeat(open.length)}</td></tr>`);
  });
  const body = `<h1><code>${escapeHtml(path.relative(site.source, file))}</code></h1>\n<table class="code">\n${rows.join('\n')}\n</table>`;
  return { target, html: page(site, file, path.basename(file), body, pageDir, 'the file itself') };
}

function writeAtomically(target, text) {
  fs.mkdirSync(path.dirname(target), { recursive: true });
  const tmp = `${target}.tmp-${process.pid}`;
  fs.writeFileSync(tmp, text);
  fs.renameSync(tmp, target);
}

function copyAssets(site) {
  const katexDist = path.dirname(require.resolve('katex/dist/katex.min.css'));
  const assets = path.join(site.pages, 'assets');
  fs.mkdirSync(path.join(assets, 'katex', 'fonts'), { recursive: true });
  fs.copyFileSync(path.join(katexDist, 'katex.min.css'), path.join(assets, 'katex', 'katex.min.css'));
  for (const font of fs.readdirSync(path.join(katexDist, 'fonts')))
    fs.copyFileSync(path.join(katexDist, 'fonts', font), path.join(assets, 'katex', 'fonts', font));
  const style = require.resolve('highlight.js/styles/github.css');
  fs.copyFileSync(style, path.join(assets, 'highlight.css'));
}

function main() {
  const { source, out, pages: pagesFolder } = parseArgs(process.argv.slice(2));
  const site = new Site(source, out, pagesFolder);
  const md = makeMarkdown();
  rewriteLinks(md, site);
  copyAssets(site);
  const queue = seedTexts(source);
  queue.forEach((f) => site.texts.add(f));
  const done = new Set();
  let pages = 0;
  while (queue.length || [...site.texts].some((f) => !done.has(f))) {
    const next = queue.shift() || [...site.texts].find((f) => !done.has(f));
    if (done.has(next)) continue;
    done.add(next);
    const { target, html } = renderText(site, md, next);
    writeAtomically(target, html);
    pages += 1;
  }
  for (const file of [...site.codeFiles].sort()) {
    const { target, html } = renderCode(site, file);
    writeAtomically(target, html);
  }
  console.log(`render_texts: ${pages} text(s) and ${site.codeFiles.size} source file(s) rendered into ` +
              `${path.relative(process.cwd(), site.pages) || site.pages}`);
  const problems = [...mathErrors.map((m) => `maths: ${m}`), ...site.problems];
  for (const p of problems) console.log(`render_texts: ${p}`);
  process.exit(problems.length ? 1 : 0);
}

main();
