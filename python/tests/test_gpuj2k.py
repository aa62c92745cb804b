"""Tests of the Python module gpuj2k (run by ctest as python_test): arrays of every supported type
and shape encode to codestreams that OpenJPEG decodes back to them (lossless) or close to them
(lossy, at the requested size), bad input raises gpuj2k.Error with the library's message, and the
GIL is released while encoding."""

import os
import subprocess
import tempfile
import threading
import time
import unittest

import numpy as np

import gpuj2k


def decode(data: bytes, suffix: str = ".j2k", out: str = ".ppm") -> np.ndarray:
    """Decodes with opj_decompress into a PNM and reads it back (8- or 16-bit, 1 or 3 channels)."""
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "in" + suffix)
        with open(src, "wb") as f:
            f.write(data)
        dst = os.path.join(d, "out" + out)
        subprocess.run(["opj_decompress", "-i", src, "-o", dst], check=True, capture_output=True)
        return read_pnm(dst)


def read_pnm(path: str) -> np.ndarray:
    with open(path, "rb") as f:
        raw = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        while raw[pos:pos + 1].isspace():
            pos += 1
        if raw[pos:pos + 1] == b"#":  # a comment, to the end of its line
            pos = raw.index(b"\n", pos)
            continue
        start = pos
        while not raw[pos:pos + 1].isspace():
            pos += 1
        fields.append(raw[start:pos])
    magic, width, height, maxval = fields[0], int(fields[1]), int(fields[2]), int(fields[3])
    channels = 3 if magic == b"P6" else 1
    dtype = np.dtype(">u2") if maxval > 255 else np.uint8
    pixels = np.frombuffer(raw[pos + 1:], dtype=dtype, count=width * height * channels)
    shape = (height, width, channels) if channels == 3 else (height, width)
    return pixels.reshape(shape).astype(np.int64)


def psnr(decoded: np.ndarray, image: np.ndarray) -> float:
    mse = np.mean((decoded - image.astype(np.int64)) ** 2)
    return float(10 * np.log10(255 ** 2 / mse))


def pattern(height: int, width: int, channels: int, dtype, bits: int) -> np.ndarray:
    rng = np.random.default_rng(7)
    y, x = np.mgrid[0:height, 0:width]
    top = (1 << bits) - 1
    base = (x * 7 + y * 3) % (top + 1)
    planes = [(base + c * 37 + rng.integers(0, 4, size=base.shape)) % (top + 1) for c in range(channels)]
    image = np.stack(planes, axis=-1) if channels > 1 else planes[0]
    return image.astype(dtype)


class EncodeArrays(unittest.TestCase):
    def test_lossless_round_trips(self):
        for dtype, bits, channels in [(np.uint8, 8, 3), (np.uint8, 8, 1), (np.uint16, 12, 3), (np.uint16, 16, 1)]:
            with self.subTest(dtype=dtype, bits=bits, channels=channels):
                image = pattern(37, 53, channels, dtype, bits)
                data = gpuj2k.encode(image, lossless=True, bits=bits)
                self.assertIsInstance(data, bytes)
                self.assertEqual(data[:4], b"\xff\x4f\xff\x51")  # SOC, SIZ
                decoded = decode(data)
                if bits not in (8, 16):  # opj_decompress writes 12-bit samples with maxval 4095
                    self.assertLessEqual(decoded.max(), (1 << bits) - 1)
                np.testing.assert_array_equal(decoded, image.astype(np.int64))

    def test_signed_samples(self):
        image = (pattern(20, 30, 1, np.int16, 10).astype(np.int32) - 512).astype(np.int16)
        data = gpuj2k.encode(image, lossless=True, bits=10)
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "s.j2k")
            with open(src, "wb") as f:
                f.write(data)
            subprocess.run(["opj_decompress", "-i", src, "-o", os.path.join(d, "s.pgx")], check=True, capture_output=True)
            pgx = [name for name in os.listdir(d) if name.endswith(".pgx")][0]
            with open(os.path.join(d, pgx), "rb") as f:
                raw = f.read()
        header_end = raw.index(b"\n") + 1
        header = raw[:header_end].split()
        self.assertIn(b"-", header[2])  # signed
        values = np.frombuffer(raw[header_end:], dtype=">i2").reshape(20, 30)
        np.testing.assert_array_equal(values, image)

    def test_views_and_copies_give_the_same_stream(self):
        image = pattern(40, 60, 3, np.uint8, 8)
        expected = gpuj2k.encode(image, rate=2.0)
        wide = np.zeros((40, 80, 3), np.uint8)
        wide[:, :60] = image
        self.assertEqual(gpuj2k.encode(wide[:, :60], rate=2.0), expected)  # padded rows, no copy
        planar = np.ascontiguousarray(image.transpose(2, 0, 1))
        self.assertEqual(gpuj2k.encode(planar.transpose(1, 2, 0), rate=2.0), expected)  # copied into shape

    def test_lossy_size_and_quality(self):
        # Smooth with noise: worth more than 1 bit per pixel, so the target is what limits the size.
        image = np.clip(pattern(128, 96, 3, np.uint8, 8).astype(np.int64) // 2 +
                        np.random.default_rng(3).integers(0, 64, size=(128, 96, 3)), 0, 255).astype(np.uint8)
        target = 128 * 96 // 8  # 1 bit per pixel, over all components
        data = gpuj2k.encode(image, rate=[0.25, 1.0], format="j2k")
        self.assertLessEqual(len(data), target)
        self.assertGreaterEqual(len(data), target * 0.99)
        ours = psnr(decode(data), image)
        # OpenJPEG at the same rate (ratio 24 of 8-bit RGB is 1 bit per pixel), as the reference.
        with tempfile.TemporaryDirectory() as d:
            src, dst = os.path.join(d, "in.ppm"), os.path.join(d, "opj.j2k")
            with open(src, "wb") as f:
                f.write(b"P6\n96 128\n255\n" + image.tobytes())
            subprocess.run(["opj_compress", "-i", src, "-o", dst, "-r", "24", "-I"], check=True, capture_output=True)
            with open(dst, "rb") as f:
                reference = psnr(decode(f.read()), image)
        self.assertGreater(ours, reference - 0.1)

    def test_jp2_and_files(self):
        image = pattern(16, 16, 3, np.uint8, 8)
        self.assertEqual(gpuj2k.encode(image, lossless=True, format="jp2")[4:8], b"jP  ")
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "in.ppm")
            with open(path, "wb") as f:
                f.write(b"P6\n16 16\n255\n" + image.tobytes())
            self.assertEqual(gpuj2k.encode_file(path, lossless=True), gpuj2k.encode(image, lossless=True))


class EncodeHt(unittest.TestCase):
    """ht=True: HTJ2K (Part 15) code-blocks, decoded by OpenJPEG and by our own decoder."""

    def test_lossless_round_trips(self):
        for dtype, bits, channels in [(np.uint8, 8, 3), (np.uint16, 12, 1), (np.uint16, 16, 3)]:
            with self.subTest(dtype=dtype, bits=bits, channels=channels):
                image = pattern(41, 29, channels, dtype, bits)
                data = gpuj2k.encode(image, lossless=True, bits=bits, ht=True)
                self.assertIn(b"\xff\x50", data[:data.index(b"\xff\x90")])  # a CAP marker in the main header
                self.assertNotEqual(data, gpuj2k.encode(image, lossless=True, bits=bits))
                np.testing.assert_array_equal(decode(data), image.astype(np.int64))
                np.testing.assert_array_equal(gpuj2k.decode(data), image)

    def test_byte_target_and_quality(self):
        image = np.clip(pattern(128, 96, 3, np.uint8, 8).astype(np.int64) // 2 +
                        np.random.default_rng(3).integers(0, 64, size=(128, 96, 3)), 0, 255).astype(np.uint8)
        target = 128 * 96 // 8  # 1 bit per pixel
        data = gpuj2k.encode(image, rate=1.0, ht=True)
        self.assertLessEqual(len(data), target)
        self.assertGreaterEqual(len(data), target * 0.995)
        ht = psnr(decode(data), image)
        self.assertAlmostEqual(psnr(gpuj2k.decode(data).astype(np.int64), image), ht, delta=0.01)
        # HT trades some coding efficiency for speed (measured: 21.82 dB against EBCOT's 21.91 dB).
        ebcot = psnr(decode(gpuj2k.encode(image, rate=1.0)), image)
        self.assertGreater(ht, ebcot - 0.5)

    def test_jph_files(self):
        image = pattern(24, 40, 3, np.uint8, 8)
        data = gpuj2k.encode(image, lossless=True, ht=True, format="jph")
        self.assertEqual(data[4:8], b"jP  ")
        self.assertEqual(data[16:20], b"ftyp")
        self.assertEqual(data[20:24], b"jph ")  # the JPH brand (T.814 Annex D)
        np.testing.assert_array_equal(decode(data, suffix=".jph"), image.astype(np.int64))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "in.ppm")
            with open(path, "wb") as f:
                f.write(b"P6\n40 24\n255\n" + image.tobytes())
            self.assertEqual(gpuj2k.encode_file(path, lossless=True, ht=True, format="jph"), data)
        with self.assertRaises(gpuj2k.Error) as caught:
            gpuj2k.encode(image, lossless=True, format="jph")
        self.assertIn("HT", str(caught.exception))


class BadInput(unittest.TestCase):
    def test_errors_carry_the_library_message(self):
        image = pattern(8, 8, 3, np.uint8, 8)
        cases = [
            (lambda: gpuj2k.encode(np.zeros((4, 4, 4, 4), np.uint8)), "dimensions"),
            (lambda: gpuj2k.encode(np.zeros((4, 4), np.float32)), "dtype"),
            (lambda: gpuj2k.encode(np.zeros((0, 4), np.uint8)), "empty"),
            (lambda: gpuj2k.encode(image, rate=-1), "rates must be positive"),
            (lambda: gpuj2k.encode(image, lossless=True, rate=1), "lossless"),
            (lambda: gpuj2k.encode(image, levels=40), "decomposition levels"),
            (lambda: gpuj2k.encode(image, bits=4), "does not fit 4-bit"),
            (lambda: gpuj2k.encode(image, format="png"), "format"),
            (lambda: gpuj2k.encode(image, rate=[0.5, 1], ht=True), "layer"),
            (lambda: gpuj2k.encode(image, rate="fast"), "rate must be a number"),
            (lambda: gpuj2k.encode_file("/nonexistent/x.ppm"), "/nonexistent/x.ppm"),
        ]
        for call, message in cases:
            with self.subTest(message=message):
                with self.assertRaises(gpuj2k.Error) as caught:
                    call()
                self.assertIn(message, str(caught.exception))
                self.assertIsInstance(caught.exception, ValueError)


class DecodeArrays(unittest.TestCase):
    def test_lossless_round_trips_through_our_decoder(self):
        for dtype, bits, channels in ((np.uint8, 8, 3), (np.uint16, 12, 1), (np.int16, 16, 3)):
            with self.subTest(dtype=dtype, bits=bits, channels=channels):
                image = pattern(37, 53, channels, dtype, bits)
                if dtype == np.int16:
                    image = (image.astype(np.int32) - 20000).astype(np.int16)
                data = gpuj2k.encode(image, lossless=True, bits=bits if dtype != np.int16 else 0)
                decoded = gpuj2k.decode(data)
                self.assertEqual(decoded.dtype, image.dtype)
                np.testing.assert_array_equal(decoded, image)

    def test_decodes_openjpeg_streams_as_openjpeg_does(self):
        image = pattern(40, 48, 3, np.uint8, 8)
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "in.ppm")
            with open(src, "wb") as f:
                f.write(b"P6\n48 40\n255\n" + image.tobytes())
            dst = os.path.join(d, "x.j2k")
            subprocess.run(["opj_compress", "-i", src, "-o", dst, "-r", "10"], check=True, capture_output=True)
            ours = gpuj2k.decode_file(dst).astype(np.int64)
            with open(dst, "rb") as f:
                theirs = decode(f.read())
        self.assertLessEqual(int(np.abs(ours - theirs).max()), 1)

    def test_windows_selections_and_reductions(self):
        image = pattern(64, 80, 3, np.uint8, 8)
        data = gpuj2k.encode(image, lossless=True)
        np.testing.assert_array_equal(gpuj2k.decode(data, region=(10, 5, 30, 20), components=[2, 0]),
                                      image[5:25, 10:40][:, :, [2, 0]])
        self.assertEqual(gpuj2k.decode(data, reduce=2).shape, (16, 20, 3))

    def test_samples_of_38_bits_come_as_int64(self):
        # Our encoder writes up to 16 bits; a deeper stream is made from an 8-bit one by its markers
        # (as tests/support/deepened_stream.h does): SIZ says 38 bits, QCD raises the guard bits
        # 2 -> 7 and the exponents by 20, so every coded bit-plane moves 25 planes up. With no
        # wavelet levels the samples are the coefficients: each non-zero one then decodes to
        # 2^25 times itself plus half the step the absent planes leave open.
        image = pattern(19, 23, 1, np.uint8, 8)
        data = bytearray(gpuj2k.encode(image, lossless=True, levels=0))
        pos = 2
        while True:
            marker, length = int.from_bytes(data[pos:pos + 2], "big"), int.from_bytes(data[pos + 2:pos + 4], "big")
            if marker == 0xFF90:
                break
            if marker == 0xFF51:
                data[pos + 40] = 37  # Ssiz: 38 bits, unsigned
            if marker == 0xFF5C:
                data[pos + 4] = 7 << 5 | (data[pos + 4] & 31)
                for k in range(pos + 5, pos + 2 + length):
                    data[k] = ((data[k] >> 3) + 20) << 3
            pos += 2 + length
        decoded = gpuj2k.decode(bytes(data))
        self.assertEqual(decoded.dtype, np.int64)
        centred = image.astype(np.int64) - 128
        raised = np.sign(centred) * ((np.abs(centred) << 25) + (1 << 24))
        np.testing.assert_array_equal(decoded, raised + (1 << 37))

    def test_bad_streams_raise_the_library_error(self):
        for data in (b"hello", gpuj2k.encode(pattern(8, 8, 1, np.uint8, 8), lossless=True)[:30]):
            with self.assertRaises(gpuj2k.Error):
                gpuj2k.decode(data)
        with self.assertRaises(gpuj2k.Error) as caught:
            gpuj2k.decode(b"x" * 10, reduce=99)
        self.assertIn("reduce 99 is outside 0..32", str(caught.exception))


class Threads(unittest.TestCase):
    def test_gil_is_released_while_encoding(self):
        image = pattern(1024, 1024, 3, np.uint8, 8)
        ticks = []
        done = threading.Event()

        def tick():
            while not done.is_set():
                ticks.append(time.monotonic())
                time.sleep(0.002)

        ticker = threading.Thread(target=tick)
        ticker.start()
        start = time.monotonic()
        results = []
        workers = [threading.Thread(target=lambda: results.append(gpuj2k.encode(image, rate=1.0, threads=1)))
                   for _ in range(2)]
        for w in workers:
            w.start()
        for w in workers:
            w.join()
        done.set()
        ticker.join()
        # Python kept running during the encodes (the GIL was free), and both gave the same bytes.
        during = [t for t in ticks if t > start + 0.01]
        self.assertGreater(len(during), 3)
        self.assertEqual(results[0], results[1])

    def test_threads_sharing_an_engine_give_the_same_bytes(self):
        image = pattern(256, 320, 3, np.uint8, 8)
        expected = gpuj2k.encode(image, rate=1.0, dwt="cpu", threads=2)
        engine = gpuj2k.Engine(threads=2)
        self.assertEqual(engine.threads, 2)
        results = [None] * 4

        def work(i):
            results[i] = gpuj2k.encode(image, rate=1.0, dwt="cpu", engine=engine)

        workers = [threading.Thread(target=work, args=(i,)) for i in range(len(results))]
        for w in workers:
            w.start()
        for w in workers:
            w.join()
        self.assertEqual(results, [expected] * len(results))


if __name__ == "__main__":
    unittest.main()
