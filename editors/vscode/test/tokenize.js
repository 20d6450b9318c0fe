#!/usr/bin/env node
// Tests the VS Code grammar (../spire.tmLanguage.json) with the TextMate
// engine VS Code itself uses (vscode-textmate on the Oniguruma WebAssembly
// build), so that what passes here is what an editor shows:
//
// 1. The extension manifest: the language, its configuration and the grammar
//    it names exist and agree.
// 2. Assertions on snippets of every construct the issue asks for, and the
//    keyword and built-in function lists checked against the compiler's own
//    (compiler/syntax/token_kinds.def, compiler/sema/builtins.cpp), so that a
//    keyword added to the lexer fails here until the grammar knows it.
// 3. Every .spire file of the repository tokenized and compared with its
//    golden scope dump, tests/golden/vscode/<path, '/' as '__'>.scopes. A
//    .spire file without a golden, or a golden without a .spire file, fails.
//    SPIRE_UPDATE_GOLDENS=1 rewrites them (and removes orphans).
// 4. No token of a repository file is invalid.* unless the file is listed in
//    INTENDED_INVALID below, and every listed file has one.
//
// Usage: node tokenize.js [--repo DIR] [--modules DIR]
//   --repo     the repository root (default: two folders up from here)
//   --modules  the node_modules holding vscode-textmate and vscode-oniguruma
//              (default: editors/vscode/node_modules)
'use strict';

const assert = require('node:assert');
const childProcess = require('node:child_process');
const crypto = require('node:crypto');
const fs = require('node:fs');
const path = require('node:path');

function parseArgs(argv) {
  const args = {
    repo: path.resolve(__dirname, '..', '..', '..'),
    modules: path.resolve(__dirname, '..', 'node_modules'),
  };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (!(key in args) || i + 1 >= argv.length) {
      throw new Error(`usage: tokenize.js [--repo DIR] [--modules DIR] (bad argument '${argv[i]}')`);
    }
    args[key] = path.resolve(argv[i + 1]);
  }
  return args;
}

const args = parseArgs(process.argv.slice(2));
const EXTENSION_DIR = path.join(args.repo, 'editors', 'vscode');
const GOLDEN_DIR = path.join(args.repo, 'tests', 'golden', 'vscode');
const UPDATE = Boolean(process.env.SPIRE_UPDATE_GOLDENS);

// Repository files that are meant to hold what the lexer rejects (stray
// characters, malformed numbers, bad escapes, unterminated strings), with
// what they hold. Anywhere else an invalid.* token is a grammar bug.
const INTENDED_INVALID = new Map([
  ['tests/fuzz/corpus/error_many_errors.spire', 'stray characters'],
  ['tests/fuzz/corpus/lex_huge_numbers.spire', 'malformed numbers'],
  ['tests/fuzz/corpus/lex_nul_bytes.spire', 'NUL bytes'],
  ['tests/fuzz/corpus/lex_unicode.spire', 'non-ASCII identifiers'],
  ['tests/fuzz/corpus/lex_unterminated_string.spire', 'an unterminated string'],
  ['tests/golden/diagnostics/stray_character.spire', 'stray characters'],
]);

// Source lines with more tokens than this (the fuzz corpus has one-line
// files of 80 000 tokens) list this many and then one line with the count
// and a hash of the rest: the golden stays readable and small, and any
// change in the rest still fails.
const MAX_TOKENS_LISTED_PER_LINE = 100;

let failures = 0;
function fail(message) {
  failures += 1;
  console.error(`FAIL: ${message}`);
}

function loadTextMate() {
  const required = ['vscode-textmate', 'vscode-oniguruma'];
  for (const name of required) {
    if (!fs.existsSync(path.join(args.modules, name))) {
      throw new Error(`${name} is not installed in ${args.modules}; run 'npm ci' in editors/vscode ` +
                      '(or run the VsCodeGrammar CTest, which installs it in the build folder)');
    }
  }
  return {
    vsctm: require(path.join(args.modules, 'vscode-textmate')),
    oniguruma: require(path.join(args.modules, 'vscode-oniguruma')),
  };
}

async function loadGrammar() {
  const { vsctm, oniguruma } = loadTextMate();
  const wasm = fs.readFileSync(path.join(args.modules, 'vscode-oniguruma', 'release', 'onig.wasm'));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const grammarPath = path.join(EXTENSION_DIR, 'spire.tmLanguage.json');
  const registry = new vsctm.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
      createOnigString: (text) => new oniguruma.OnigString(text),
    }),
    loadGrammar: async (scopeName) =>
      scopeName === 'source.spire' ? vsctm.parseRawGrammar(fs.readFileSync(grammarPath, 'utf8'), grammarPath) : null,
  });
  const grammar = await registry.loadGrammar('source.spire');
  if (!grammar) throw new Error(`could not load ${grammarPath}`);
  return { grammar, INITIAL: vsctm.INITIAL };
}

// Lines as VS Code splits them (a leading byte order mark is not text).
function splitLines(text) {
  return text.replace(/^\uFEFF/, '').split(/\r\n|\r|\n/);
}

// [{line, start, end, text, scopes}] for a whole text; `line` is 1-based,
// `start` and `end` 0-based UTF-16 offsets as the editor counts them.
function tokenize(tm, text) {
  const tokens = [];
  let state = tm.INITIAL;
  splitLines(text).forEach((lineText, index) => {
    const result = tm.grammar.tokenizeLine(lineText, state);
    for (const token of result.tokens) {
      const end = Math.min(token.endIndex, lineText.length);
      if (end <= token.startIndex) continue;
      tokens.push({
        line: index + 1,
        start: token.startIndex,
        end,
        text: lineText.slice(token.startIndex, end),
        scopes: token.scopes,
      });
    }
    state = result.ruleStack;
  });
  return tokens;
}

// One line per token: `line:first-last scopes "text"`, columns 1-based and
// inclusive, without the root scope every token has. Whitespace-only tokens
// are left out: they show nothing.
function dumpToken(token) {
  return `${token.line}:${token.start + 1}-${token.end} ${token.scopes.slice(1).join(' ')} ${JSON.stringify(token.text)}`;
}

function scopeDump(tokens) {
  const out = [];
  let line = [];
  const flush = () => {
    const listed = line.slice(0, MAX_TOKENS_LISTED_PER_LINE);
    out.push(...listed.map(dumpToken));
    const rest = line.slice(MAX_TOKENS_LISTED_PER_LINE);
    if (rest.length > 0) {
      const hash = crypto.createHash('sha256').update(rest.map(dumpToken).join('\n')).digest('hex').slice(0, 16);
      out.push(`${rest[0].line}: ${rest.length} more tokens, sha256 ${hash}`);
    }
    line = [];
  };
  for (const token of tokens) {
    if (/^\s*$/.test(token.text)) continue;
    if (line.length > 0 && line[0].line !== token.line) flush();
    line.push(token);
  }
  flush();
  return out.join('\n') + '\n';
}

function hasScope(token, prefix) {
  return token.scopes.some((scope) => scope.startsWith(prefix));
}

// ---------------------------------------------------------------------------
// 1. The manifest

function checkManifest() {
  const manifest = JSON.parse(fs.readFileSync(path.join(EXTENSION_DIR, 'package.json'), 'utf8'));
  const languages = (manifest.contributes && manifest.contributes.languages) || [];
  const grammars = (manifest.contributes && manifest.contributes.grammars) || [];
  const spire = languages.find((language) => language.id === 'spire');
  if (!spire) return fail('package.json contributes no language with id "spire"');
  if (!(spire.extensions || []).includes('.spire')) fail('the spire language does not claim the .spire extension');
  const configPath = path.join(EXTENSION_DIR, spire.configuration || '');
  if (!spire.configuration || !fs.existsSync(configPath)) {
    fail(`the language configuration ${spire.configuration} does not exist`);
  } else {
    const config = JSON.parse(fs.readFileSync(configPath, 'utf8'));
    assertEqual(config.comments, { lineComment: '//', blockComment: ['/*', '*/'] }, 'language configuration comments');
    for (const key of ['brackets', 'autoClosingPairs', 'surroundingPairs', 'folding']) {
      if (!config[key]) fail(`the language configuration has no ${key}`);
    }
  }
  const grammar = grammars.find((entry) => entry.language === 'spire');
  if (!grammar) return fail('package.json contributes no grammar for the spire language');
  if (grammar.scopeName !== 'source.spire') fail(`the grammar's scopeName is ${grammar.scopeName}, not source.spire`);
  const grammarPath = path.join(EXTENSION_DIR, grammar.path || '');
  if (!grammar.path || !fs.existsSync(grammarPath)) return fail(`the grammar ${grammar.path} does not exist`);
  const raw = JSON.parse(fs.readFileSync(grammarPath, 'utf8'));
  if (raw.scopeName !== grammar.scopeName) fail(`${grammar.path} says scopeName ${raw.scopeName}`);
  return undefined;
}

function assertEqual(actual, expected, what) {
  try {
    assert.deepStrictEqual(actual, expected);
  } catch {
    fail(`${what}: expected ${JSON.stringify(expected)}, got ${JSON.stringify(actual)}`);
  }
}

// ---------------------------------------------------------------------------
// 2. Snippets

// Checks that in `source`, the `occurrence`-th token whose text is `text`
// (tokens may split a word only where scopes change, so the text is matched
// against the concatenation of adjacent tokens) has a scope starting with
// `scope` (or, with `not`, none).
function expectScope(tm, source, text, scope, { occurrence = 1, not = false } = {}) {
  const tokens = tokenize(tm, source);
  const found = findText(tokens, text, occurrence);
  const where = `in ${JSON.stringify(source)}, ${JSON.stringify(text)}`;
  if (!found) return fail(`${where} is not a token sequence: ${tokens.map((t) => JSON.stringify(t.text)).join(' ')}`);
  for (const token of found) {
    if (hasScope(token, scope) === not) {
      fail(`${where}: token ${JSON.stringify(token.text)} ${not ? 'has' : 'lacks'} a scope ${scope}*; ` +
           `it has ${token.scopes.join(' ')}`);
      return undefined;
    }
  }
  return undefined;
}

function findText(tokens, text, occurrence) {
  let seen = 0;
  for (let i = 0; i < tokens.length; ++i) {
    let joined = '';
    for (let j = i; j < tokens.length && tokens[j].line === tokens[i].line && joined.length < text.length; ++j) {
      joined += tokens[j].text;
      if (joined === text && ++seen === occurrence) return tokens.slice(i, j + 1);
    }
  }
  return null;
}

function checkSnippets(tm) {
  const E = (source, text, scope, options) => expectScope(tm, source, text, scope, options);

  // The issue's own example: world annotation, variation, comment.
  const decl = '@Fragment vec3 lighting:ggx = x; // c';
  E(decl, '@Fragment', 'meta.annotation.world');
  E(decl, 'Fragment', 'storage.type.annotation.world');
  E(decl, 'vec3', 'storage.type.builtin');
  E(decl, 'lighting', 'variable.other.declaration');
  E(decl, 'ggx', 'entity.name.variation');
  E(decl, '// c', 'comment.line.double-slash');
  E(decl, 'x', 'comment', { not: true });
  E('@ World float f;', 'World', 'storage.type.annotation.world');

  // Attributes; an index is not one.
  const attrs = '[Format: "RGBA8"] [TextureSize: "256"][Cached] abstract @PrebakeTex vec4 albedo;';
  E(attrs, '"RGBA8"', 'string.quoted.double');
  E(attrs, 'Format', 'entity.other.attribute-name');
  E(attrs, 'TextureSize', 'entity.other.attribute-name');
  E(attrs, 'Cached', 'entity.other.attribute-name');
  E(attrs, 'abstract', 'storage.modifier');
  E(attrs, 'PrebakeTex', 'storage.type.annotation.world');
  E('[Role: "instance"] abstract world InstanceUniform;', 'InstanceUniform', 'entity.name.type.world');
  E('[Hint: "say \\"hi\\" \\\\ bye"] [Other] vec3 baked;', '\\"', 'constant.character.escape');
  E('    [Fast]', 'Fast', 'entity.other.attribute-name');
  E('x = m[0][i] + a[j];', 'i', 'entity.other.attribute-name', { not: true });
  E('x = m[0][i] + a[j];', 'j', 'entity.other.attribute-name', { not: true });
  E('x = f(a)[k];', 'k', 'entity.other.attribute-name', { not: true });

  // Pipelines: worlds, strategies, imports.
  E('pipeline EnginePipeline {', 'pipeline', 'storage.type.pipeline');
  E('pipeline EnginePipeline {', 'EnginePipeline', 'entity.name.type.pipeline');
  const world = 'world Vertex : "GLSL" export vertexExport(projPos);';
  E(world, 'world', 'storage.type.world');
  E(world, 'Vertex', 'entity.name.type.world');
  E(world, '"GLSL"', 'string.quoted.double');
  E(world, 'export', 'storage.modifier');
  E(world, 'vertexExport', 'entity.name.function.strategy');
  const imp = 'import PrebakeTex->Fragment using textureImport(vert_uv);';
  E(imp, 'import', 'keyword.other.import');
  E(imp, 'PrebakeTex', 'entity.name.type.world');
  E(imp, '->', 'keyword.operator.import-arrow');
  E(imp, 'Fragment', 'entity.name.type.world');
  E(imp, 'using', 'keyword.other.using');
  E(imp, 'textureImport', 'entity.name.function.strategy');
  E('abstract export @Fragment vec4 output;', 'export', 'storage.modifier');
  E('abstract export @Fragment vec4 output;', 'vec4', 'entity.name.function.strategy', { not: true });
  E('abstract export @Fragment vec4 output;', 'output', 'variable.other.declaration');

  // Shaders, inheritance, groups, includes.
  const shader = 'shader LodLQ : LodBase finalizes Vertex, Fragment {';
  E(shader, 'shader', 'storage.type.shader');
  E(shader, 'LodLQ', 'entity.name.type.shader');
  E(shader, 'LodBase', 'entity.other.inherited-class');
  E(shader, 'finalizes', 'keyword');
  E(shader, 'Fragment', 'entity.name.type.world');
  E('shader Couch using EnginePipeline {', 'EnginePipeline', 'entity.name.type.pipeline');
  E('shader LodMQ : LodBase\n    finalizes Vertex {', 'Vertex', 'entity.name.type.world');
  E('group G { optional shader A; }', 'optional', 'storage.modifier');
  E('group G { optional shader A; }', 'G', 'entity.name.type.group');
  E('group G { optional shader A; }', 'A', 'entity.name.type.shader');
  E('using "../pipelines/engine.spire";', 'using', 'keyword.other.using');
  E('using "../pipelines/engine.spire";', '"../pipelines/engine.spire"', 'string.quoted.double');
  E('struct Light { vec3 color; };', 'Light', 'entity.name.type.struct');

  // Functions and GLSL bodies.
  const fn = 'float[3] triple(const in Light light, out float w[3]) { return smoothstep(0.0, 1.0, f(x)).x; }';
  E(fn, 'float', 'storage.type.builtin');
  E(fn, 'triple', 'entity.name.function');
  E(fn, 'const', 'storage.modifier');
  E(fn, 'in', 'storage.modifier');
  E(fn, 'Light', 'entity.name.type');
  E(fn, 'light', 'variable.other.declaration');
  E(fn, 'return', 'keyword.control');
  E(fn, 'smoothstep', 'support.function.builtin');
  E(fn, 'f', 'entity.name.function.call');
  E(fn, 'x', 'variable.other.member', { occurrence: 2 });
  E('r = p ? a : b;', 'b', 'entity.name.variation', { not: true });
  E('r = p ? a : b;', '?', 'keyword.operator.ternary');
  E('if (a && !b) discard; else x <<= 2;', 'discard', 'keyword.control');
  E('if (a && !b) discard; else x <<= 2;', '<<=', 'keyword.operator.assignment');
  E('bool b = true;', 'true', 'constant.language');
  E('mat4x3 m = mat4x3(1.0); sampler2DArray s;', 'mat4x3', 'storage.type.builtin', { occurrence: 2 });
  E('sampler2DArray s;', 'sampler2DArray', 'storage.type.builtin');

  // Numbers as the lexer reads them (docs/language.md, "Literals").
  for (const n of ['1.5e-3', '1.0', '.5', '2.', '1e-3', '2.f', '1.5F', '1e+10f']) {
    E(`x = ${n};`, n, 'constant.numeric.float');
  }
  E('x = 0x1Fu;', '0x1Fu', 'constant.numeric.integer.hexadecimal');
  E('x = 017u;', '017u', 'constant.numeric.integer.octal');
  E('x = 42;', '42', 'constant.numeric.integer.decimal');
  E('x = 0;', '0', 'constant.numeric.integer.decimal');
  for (const bad of ['1abc', '2f', '0x', '1e', '09', '1.0lf', '0xFFg']) {
    E(`x = ${bad};`, bad, 'invalid.illegal.numeric');
  }
  E('vec3 v3 = x;', 'v3', 'constant.numeric', { not: true });

  // Comments and strings.
  E('/* a\n b */ float x;', ' b ', 'comment.block');
  E('/* a\n b */ float x;', 'float', 'storage.type.builtin');
  E('x = 1; /* c */ y = 2;', 'y', 'comment', { not: true });
  E('using "a\\qb";', '\\q', 'invalid.illegal.unknown-escape');
  E('using "never closed', '"never closed', 'invalid.illegal.unterminated-string');

  // Stray characters: invalid outside comments and strings only.
  E('float x = 1.0 # 2;', '#', 'invalid.illegal.character');
  E('float x = $y;', '$', 'invalid.illegal.character');
  E('float \u00e9 = 1.0;', '\u00e9', 'invalid.illegal.character');
  E('// caf\u00e9 #', ' caf\u00e9 #', 'invalid', { not: true });
  E('[Doc: "\u65e5\u672c"] float x;', '\u65e5\u672c', 'invalid', { not: true });
}

// Every keyword of the lexer is highlighted as one, and words the lexer does
// not reserve are not.
function checkKeywords(tm) {
  const def = fs.readFileSync(path.join(args.repo, 'compiler', 'syntax', 'token_kinds.def'), 'utf8');
  const keywords = [...def.matchAll(/^SPIRE_KEYWORD\(\w+,\s*"(\w+)"\)/gm)].map((m) => m[1]);
  if (keywords.length < 20) fail(`found only ${keywords.length} keywords in token_kinds.def`);
  for (const keyword of keywords) {
    const [token] = tokenize(tm, keyword);
    const ok = token && token.text === keyword &&
               token.scopes.some((s) => /^(keyword|storage\.(type|modifier)|constant\.language)\./.test(s));
    if (!ok) fail(`the lexer's keyword '${keyword}' is not highlighted as a keyword: ${token && token.scopes.join(' ')}`);
  }
  for (const word of ['module', 'inline', 'output', 'input', 'uniform', 'varying', 'double']) {
    if (keywords.includes(word)) continue;
    const [token] = tokenize(tm, word);
    if (token.scopes.some((s) => /^(keyword|storage\.modifier)\./.test(s))) {
      fail(`'${word}' is highlighted as a keyword, but the lexer does not reserve it: ${token.scopes.join(' ')}`);
    }
  }
}

// Every built-in function of the compiler's table is highlighted in a call.
function checkBuiltinFunctions(tm) {
  const source = fs.readFileSync(path.join(args.repo, 'compiler', 'sema', 'builtins.cpp'), 'utf8');
  // The table's only string literals are function names.
  const names = new Set([...source.matchAll(/"([A-Za-z_]\w*)"/g)].map((m) => m[1]));
  if (names.size < 100) fail(`found only ${names.size} built-in functions in builtins.cpp`);
  for (const name of names) {
    const token = tokenize(tm, `x = ${name}(a);`).find((t) => t.text === name);
    if (!token || !hasScope(token, 'support.function.builtin')) {
      fail(`the built-in function '${name}' is not highlighted as one: ${token && token.scopes.join(' ')}`);
    }
  }
}

// ---------------------------------------------------------------------------
// 3. and 4. The repository's files

// The tracked .spire files (a scratch file of one's own needs no golden),
// or, outside a git checkout (a source tarball), every .spire file but those
// of build folders and node_modules.
function spireFiles() {
  let files;
  try {
    const listed = childProcess.execFileSync('git', ['ls-files', '-z', '--', '*.spire'],
                                             { cwd: args.repo, stdio: ['ignore', 'pipe', 'ignore'] });
    files = listed.toString('utf8').split('\0').filter((file) => file && fs.existsSync(path.join(args.repo, file)));
  } catch {
    files = walkSpireFiles('');
  }
  return files.sort();
}

function walkSpireFiles(relative) {
  const found = [];
  for (const entry of fs.readdirSync(path.join(args.repo, relative), { withFileTypes: true })) {
    const file = relative ? `${relative}/${entry.name}` : entry.name;
    if (entry.isDirectory()) {
      if (!/^(build.*|node_modules|\..*)$/.test(entry.name)) found.push(...walkSpireFiles(file));
    } else if (entry.isFile() && entry.name.endsWith('.spire')) {
      found.push(file);
    }
  }
  return found;
}

function goldenName(file) {
  return file.split('/').join('__') + '.scopes';
}

function showDiff(file, expected, actual) {
  const e = expected.split('\n');
  const a = actual.split('\n');
  let i = 0;
  while (i < e.length && i < a.length && e[i] === a[i]) ++i;
  const lines = [`${file}: the scopes differ from the golden, first at golden line ${i + 1}:`];
  for (let k = i; k < Math.min(i + 5, Math.max(e.length, a.length)); ++k) {
    if (e[k] === a[k]) {
      lines.push(`    ${e[k]}`);
      continue;
    }
    if (k < e.length) lines.push(`  - ${e[k]}`);
    if (k < a.length) lines.push(`  + ${a[k]}`);
  }
  lines.push('  (after an intended grammar change: SPIRE_UPDATE_GOLDENS=1 and review the git diff)');
  return lines.join('\n');
}

function checkRepositoryFiles(tm) {
  const files = spireFiles();
  if (files.length === 0) fail('git ls-files found no .spire file');
  const goldens = new Map();
  for (const file of files) {
    const name = goldenName(file);
    if (goldens.has(name)) fail(`${file} and ${goldens.get(name)} map to the same golden ${name}`);
    goldens.set(name, file);
  }
  if (UPDATE) fs.mkdirSync(GOLDEN_DIR, { recursive: true });
  const onDisk = fs.existsSync(GOLDEN_DIR) ? fs.readdirSync(GOLDEN_DIR) : [];
  for (const name of onDisk) {
    if (goldens.has(name)) continue;
    if (UPDATE) {
      fs.unlinkSync(path.join(GOLDEN_DIR, name));
      console.log(`removed ${name}: no such .spire file`);
    } else {
      fail(`tests/golden/vscode/${name} has no .spire file (run with SPIRE_UPDATE_GOLDENS=1 to remove it)`);
    }
  }

  for (const file of files) {
    const tokens = tokenize(tm, fs.readFileSync(path.join(args.repo, file), 'utf8'));
    const actual = scopeDump(tokens);
    const goldenPath = path.join(GOLDEN_DIR, goldenName(file));
    const expected = fs.existsSync(goldenPath) ? fs.readFileSync(goldenPath, 'utf8') : null;
    if (UPDATE) {
      if (expected !== actual) {
        fs.writeFileSync(goldenPath, actual);
        console.log(`${expected === null ? 'wrote' : 'updated'} ${path.relative(args.repo, goldenPath)}`);
      }
    } else if (expected === null) {
      fail(`${file} has no golden ${path.relative(args.repo, goldenPath)} (run with SPIRE_UPDATE_GOLDENS=1)`);
    } else if (expected !== actual) {
      fail(showDiff(file, expected, actual));
    }

    const invalid = tokens.filter((token) => hasScope(token, 'invalid'));
    if (INTENDED_INVALID.has(file)) {
      if (invalid.length === 0) fail(`${file} should hold ${INTENDED_INVALID.get(file)}, but no token is invalid.*`);
    } else if (invalid.length > 0) {
      const t = invalid[0];
      fail(`${file}:${t.line}:${t.start + 1}: ${JSON.stringify(t.text)} is ${t.scopes.join(' ')}` +
           ` (${invalid.length} invalid token(s) in all)`);
    }
  }
  for (const file of INTENDED_INVALID.keys()) {
    if (!files.includes(file)) fail(`INTENDED_INVALID lists ${file}, which is not a .spire file of the repository`);
  }
  return files.length;
}

async function main() {
  checkManifest();
  const tm = await loadGrammar();
  checkSnippets(tm);
  checkKeywords(tm);
  checkBuiltinFunctions(tm);
  const count = checkRepositoryFiles(tm);
  if (failures > 0) {
    console.error(`${failures} failure(s); ${count} .spire files tokenized`);
    process.exit(1);
  }
  console.log(`VS Code grammar: ${count} .spire files tokenized and matching their goldens; snippets, ` +
              'keywords and built-in functions checked');
}

main().catch((error) => {
  console.error(error.stack || String(error));
  process.exit(1);
});
