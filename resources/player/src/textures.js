// ---------------------------------------------------------------- textures: decoding, size limit, mipmaps
// A panorama reaches the GPU decoded off the main thread (HTMLImageElement.decode, then createImageBitmap,
// which also resamples; a 2-D canvas where it is missing), never larger than the GPU's MAX_TEXTURE_SIZE
// (export allows 16 384 px, phones take 4 096: a larger image is scaled down, not refused), and mipmapped, so
// that a zoomed-out view does not shimmer. WebGL1 makes mipmaps of power-of-two sizes only: there the image is
// resampled to the nearest power of two; WebGL2 takes any size.

let textureLimits = null;
function gpuLimits() {
  if (!textureLimits) {
    const anisotropy = gl.getExtension('EXT_texture_filter_anisotropic');
    textureLimits = {
      webgl2: typeof WebGL2RenderingContext !== 'undefined' && gl instanceof WebGL2RenderingContext,
      maxTextureSize: gl.getParameter(gl.MAX_TEXTURE_SIZE),
      anisotropy,
      maxAnisotropy: anisotropy ? Math.min(8, gl.getParameter(anisotropy.MAX_TEXTURE_MAX_ANISOTROPY_EXT)) : 1,
    };
  }
  return textureLimits;
}

const isPowerOfTwo = (n) => n > 0 && (n & (n - 1)) === 0;
// The nearest power of two in ratio (1500 -> 2048, 1400 -> 1024), at most `limit`.
const nearestPowerOfTwo = (n, limit) => Math.min(limit, 2 ** Math.round(Math.log2(Math.max(1, n))));

// The size an image of width x height is uploaded at: within MAX_TEXTURE_SIZE, keeping its aspect ratio, and
// powers of two under WebGL1 (for mipmaps and the REPEAT wrap of the equirectangular seam).
function textureSizeFor(width, height) {
  const { webgl2, maxTextureSize } = gpuLimits();
  const scale = Math.min(1, maxTextureSize / width, maxTextureSize / height);
  const w = Math.max(1, Math.round(width * scale)), h = Math.max(1, Math.round(height * scale));
  if (webgl2) return { width: w, height: h };
  return { width: nearestPowerOfTwo(w, maxTextureSize), height: nearestPowerOfTwo(h, maxTextureSize) };
}

// Decodes `image` (an HTMLImageElement, loaded) into what texImage2D takes at the size textureSizeFor gives.
function decodeForTexture(image) {
  const width = image.naturalWidth || image.width, height = image.naturalHeight || image.height;
  const size = textureSizeFor(width, height);
  const same = size.width === width && size.height === height;
  const decoded = typeof image.decode === 'function' ? image.decode().catch(() => {}) : Promise.resolve();
  return decoded.then(() => {
    if (typeof createImageBitmap === 'function') {
      const options = { imageOrientation: 'none', premultiplyAlpha: 'none', colorSpaceConversion: 'default' };
      if (!same) Object.assign(options, { resizeWidth: size.width, resizeHeight: size.height, resizeQuality: 'high' });
      return createImageBitmap(image, options).catch(() => resampled(image, size, same));
    }
    return resampled(image, size, same);
  });
}

// The fallback of browsers without createImageBitmap: the element itself, or a canvas at the texture size.
function resampled(image, size, same) {
  if (same) return image;
  const c = document.createElement('canvas');
  c.width = size.width; c.height = size.height;
  const ctx = c.getContext('2d');
  ctx.imageSmoothingQuality = 'high';
  ctx.drawImage(image, 0, 0, size.width, size.height);
  return c;
}

// A mipmapped texture of `source` (from decodeForTexture). `repeatS`: the equirectangular image wraps round
// in azimuth. Throws what texImage2D throws (a SecurityError for an image the page may not read).
function makeMipmappedTexture(source, repeatS) {
  const limits = gpuLimits();
  const w = source.width, h = source.height;
  const mipmaps = limits.webgl2 || (isPowerOfTwo(w) && isPowerOfTwo(h));
  const t = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, t);
  try {
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, source);
  } catch (e) {
    gl.deleteTexture(t);
    throw e;
  }
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, repeatS && mipmaps ? gl.REPEAT : gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, mipmaps ? gl.LINEAR_MIPMAP_LINEAR : gl.LINEAR);
  if (mipmaps) gl.generateMipmap(gl.TEXTURE_2D);
  if (limits.anisotropy)
    gl.texParameterf(gl.TEXTURE_2D, limits.anisotropy.TEXTURE_MAX_ANISOTROPY_EXT, limits.maxAnisotropy);
  if (typeof source.close === 'function') source.close();  // an ImageBitmap: its memory back at once
  return { texture: t, width: w, height: h, mipmaps, repeat: repeatS && mipmaps };
}
