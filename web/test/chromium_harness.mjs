// What the browser tests share: the repository served over HTTP to headless Chromium (Debian's
// chromium, or the binary M4D_CHROMIUM names, driven by puppeteer-core), pages whose errors
// are collected, and PSNR of a page's canvas against a PNG. A helper, not a test file: it has
// no tests, so `node --test web/test/` runs it harmlessly.
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { serve } from '../tools/serve.mjs';

/** The repository's root directory (with a trailing separator). */
export const root = fileURLToPath(new URL('../../', import.meta.url));

/**
 * Serves the repository on 127.0.0.1 and launches headless Chromium. Returns { server, base
 * (the server's http URL, no trailing slash), browser, close() }; close() ends both.
 */
export async function startChromium() {
  const server = await serve(root);
  const base = `http://127.0.0.1:${server.address().port}`;
  let browser;
  try {
    // No GPU here: WebGL2 on SwiftShader, Chromium's CPU rasterizer.
    browser = await puppeteer.launch({
      executablePath: process.env.M4D_CHROMIUM || '/usr/bin/chromium',
      headless: true,
      args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
    });
  } catch (e) {
    server.close();
    throw e;
  }
  return {
    server, base, browser,
    async close() {
      await browser.close();
      server.close();
    },
  };
}

/**
 * Opens url in a new page of browser; the messages of errors thrown in the page, from its
 * loading on, gather in page.problems.
 */
export async function openPage(browser, url) {
  const page = await browser.newPage();
  page.problems = [];
  page.on('pageerror', (e) => page.problems.push(e.message));
  await page.goto(url);
  return page;
}

/**
 * PSNR in dB of the page's canvas, as window[global].readRgb() reads it (RGB, top row first),
 * against a PNG (bytes) decoded by the browser; -1 if their sizes differ.
 */
export async function psnrAgainstPng(page, png, global) {
  return page.evaluate(async (base64, name) => {
    const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
    const image = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const reference = context.getImageData(0, 0, image.width, image.height).data;
    const drawn = window[name].readRgb();
    if (drawn.length !== 3 * image.width * image.height) return -1;
    let sum = 0;
    for (let p = 0; p < image.width * image.height; ++p) {
      for (let c = 0; c < 3; ++c) sum += (drawn[3 * p + c] - reference[4 * p + c]) ** 2;
    }
    const mse = sum / drawn.length;
    return mse === 0 ? Infinity : 10 * Math.log10((255 * 255) / mse);
  }, png.toString('base64'), global);
}
