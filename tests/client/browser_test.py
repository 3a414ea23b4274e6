#!/usr/bin/python3
"""A real browser opens the report: headless Chromium (Debian's chromium, chromium-driver and
python3-selenium) loads each report.html given and checks that every image decodes
(naturalWidth > 0), every link and anchor resolves (a relative file exists, an #anchor names an
element), the console holds no error, and the verdict is the first thing on the page (the first
heading after the title is "Verdict", its first item starts "verdict:"). With
TWINFLOW_CLIENT_PNG=FILE it keeps a screenshot of the first report. Exit 77 (skipped) without
Chromium.
    browser_test.py REPORT.html [REPORT.html ...]
"""
import os
import shutil
import sys
import tempfile
import urllib.parse


def skip(why):
    print(f'skipped: {why} (Debian: apt-get install chromium chromium-driver python3-selenium)')
    sys.exit(77)


try:
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By
except ImportError:
    skip('no selenium')
chromium = shutil.which('chromium') or shutil.which('chromium-browser')
driver_path = shutil.which('chromedriver')
if not chromium or not driver_path:
    skip('no chromium or chromedriver')


def browser(profile):
    options = Options()
    options.binary_location = chromium
    for flag in ('--headless=new', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage',
                 '--disable-background-networking', '--disable-component-update', '--disable-sync',
                 '--no-first-run', '--allow-file-access-from-files', f'--user-data-dir={profile}',
                 '--window-size=1200,1600'):
        options.add_argument(flag)
    options.set_capability('goog:loggingPrefs', {'browser': 'ALL'})
    return webdriver.Chrome(service=Service(driver_path), options=options)


def check(driver, report):
    problems = []
    url = 'file://' + urllib.parse.quote(os.path.abspath(report))
    driver.get(url)
    for img in driver.find_elements(By.TAG_NAME, 'img'):
        ok = driver.execute_script('return arguments[0].complete && arguments[0].naturalWidth > 0', img)
        if not ok:
            problems.append(f'image {img.get_attribute("src")} does not decode')
    base = os.path.dirname(os.path.abspath(report))
    for a in driver.find_elements(By.CSS_SELECTOR, 'a[href]'):
        href = a.get_attribute('href')
        parsed = urllib.parse.urlparse(href)
        if parsed.scheme == 'file':
            path = urllib.parse.unquote(parsed.path)
            if not os.path.exists(path):
                problems.append(f'link {href}: no such file')
            if parsed.fragment and path == os.path.abspath(report):
                found = driver.execute_script(
                    'return document.getElementById(arguments[0]) || '
                    'document.getElementsByName(arguments[0]).length > 0', parsed.fragment)
                if not found:
                    problems.append(f'anchor #{parsed.fragment}: no such element')
        elif parsed.scheme in ('http', 'https'):
            problems.append(f'link {href}: leaves the report (no network in its reader\'s hands)')
    for entry in driver.get_log('browser'):
        if entry.get('level') == 'SEVERE':
            problems.append(f'console: {entry.get("message")}')
    headings = [h.text for h in driver.find_elements(By.CSS_SELECTOR, 'h1, h2')]
    if len(headings) < 2 or headings[1] != 'Verdict':
        problems.append(f'the verdict is not first: headings {headings[:3]}')
    first_item = driver.execute_script(
        'const h = [...document.querySelectorAll("h2")].find(e => e.textContent == "Verdict");'
        'const list = h && h.nextElementSibling; return list ? list.innerText : "";')
    if not first_item.lower().lstrip().startswith('verdict'):
        problems.append(f'the verdict section does not open with the verdict: {first_item[:80]!r}')
    print(f'{report}: {len(driver.find_elements(By.TAG_NAME, "img"))} images, '
          f'{len(driver.find_elements(By.CSS_SELECTOR, "a[href]"))} links, {len(problems)} problems')
    return problems


def main():
    reports = sys.argv[1:]
    if not reports:
        print(__doc__)
        return 2
    profile = tempfile.mkdtemp(prefix='twinflow-chromium-')
    driver = browser(profile)
    problems = []
    try:
        for i, report in enumerate(reports):
            problems += check(driver, report)
            if i == 0 and os.environ.get('TWINFLOW_CLIENT_PNG'):
                driver.save_screenshot(os.environ['TWINFLOW_CLIENT_PNG'])
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
    for p in problems:
        print('FAIL:', p)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
