#!/usr/bin/env node
// Validates glTF 2.0 files (.gltf, .glb) with the Khronos glTF validator (npm gltf-validator, pinned
// in package-lock.json). Used by scripts/validate-gltf; see its header for the contract.
//
//   node validate.js [--strict] [--verbose] FILE...
//
// Per file: one summary line "FILE: N errors, N warnings, N infos, N hints", then one line per error
// and warning "  SEVERITY CODE POINTER: MESSAGE" (infos and hints too with --verbose). External
// buffers and images are resolved relative to the file's folder.
// Exit status: 0 when no file has errors (with --strict: no errors and no warnings), 1 otherwise
// (including a file that cannot be read), 2 for bad usage.
'use strict';
const fs = require('fs');
const path = require('path');

const kUsage = 'usage: validate-gltf [--strict] [--verbose] FILE.gltf|FILE.glb...';
const kSeverityNames = ['ERROR', 'WARNING', 'INFO', 'HINT'];

function parseArguments(argv) {
  const options = {strict: false, verbose: false, files: []};
  let only_files = false;
  for (const arg of argv) {
    if (!only_files && arg === '--') {
      only_files = true;
    } else if (!only_files && arg === '--strict') {
      options.strict = true;
    } else if (!only_files && arg === '--verbose') {
      options.verbose = true;
    } else if (!only_files && (arg === '--help' || arg === '-h')) {
      options.help = true;
    } else if (!only_files && arg.startsWith('-')) {
      throw new Error(`unknown option '${arg}'`);
    } else {
      options.files.push(arg);
    }
  }
  if (!options.help && options.files.length === 0) {
    throw new Error('no FILE given');
  }
  return options;
}

function loadValidator() {
  try {
    return require('gltf-validator');
  } catch (error) {
    process.stderr.write(
        'validate-gltf: the npm package gltf-validator is not installed in ' + __dirname +
        ' (run scripts/install-deps)\n');
    process.exit(2);
  }
}

// Returns true when the file passes (no errors; with strict, no warnings either).
async function validateFile(validator, file, options) {
  let bytes;
  try {
    bytes = fs.readFileSync(file);
  } catch (error) {
    process.stdout.write(`${file}: cannot read: ${error.code || error.message}\n`);
    return false;
  }
  const folder = path.dirname(path.resolve(file));
  let report;
  try {
    report = await validator.validateBytes(new Uint8Array(bytes), {
      uri: path.basename(file),
      maxIssues: 0,
      writeTimestamp: false,
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        const resource = path.resolve(folder, decodeURIComponent(uri));
        fs.readFile(resource, (error, data) => {
          if (error) {
            reject(`cannot read '${uri}' (${resource}): ${error.code || error.message}`);
          } else {
            resolve(new Uint8Array(data));
          }
        });
      }),
    });
  } catch (error) {
    // The validator rejects when it cannot even detect the format.
    process.stdout.write(`${file}: not glTF or GLB: ${error}\n`);
    return false;
  }
  const issues = report.issues;
  process.stdout.write(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
                       `${issues.numInfos} infos, ${issues.numHints} hints\n`);
  for (const message of issues.messages) {
    if (message.severity > 1 && !options.verbose) continue;
    const where = message.pointer !== undefined ? message.pointer :
        message.offset !== undefined ? `@${message.offset}` : '-';
    const severity = kSeverityNames[message.severity] || `SEVERITY${message.severity}`;
    process.stdout.write(`  ${severity} ${message.code} ${where}: ${message.message}\n`);
  }
  return issues.numErrors === 0 && (!options.strict || issues.numWarnings === 0);
}

async function main() {
  let options;
  try {
    options = parseArguments(process.argv.slice(2));
  } catch (error) {
    process.stderr.write(`validate-gltf: ${error.message}\n${kUsage}\n`);
    return 2;
  }
  if (options.help) {
    process.stdout.write(kUsage + '\n');
    return 0;
  }
  const validator = loadValidator();
  let all_pass = true;
  for (const file of options.files) {
    if (!(await validateFile(validator, file, options))) all_pass = false;
  }
  return all_pass ? 0 : 1;
}

main().then((status) => {
  process.exitCode = status;
});
