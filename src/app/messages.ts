/**
 * The page's messages: an alert (errors, dismissible) and a notice (a few
 * seconds). Both float over the top of the view instead of pushing it down:
 * a message must never resize the viewport, since a new render size restarts
 * accumulation (that is how a rejected file used to throw away the samples).
 * Untrusted text (file names, issues, logs) is only set through textContent.
 */
import { formatIssue, type SceneIssue } from '../scene/schema';

const $ = (id: string) => document.getElementById(id)!;

export function showError(title: string, lines: string[] = [], log?: string): void {
  const alertBox = $('error');
  alertBox.replaceChildren();
  const dismiss = document.createElement('button');
  dismiss.className = 'dismiss';
  dismiss.type = 'button';
  dismiss.textContent = '×';
  dismiss.setAttribute('aria-label', 'Dismiss');
  dismiss.addEventListener('click', clearError);
  const heading = document.createElement('strong');
  heading.textContent = title;
  alertBox.append(dismiss, heading);
  if (lines.length) {
    const list = document.createElement('ul');
    for (const line of lines) {
      const item = document.createElement('li');
      item.textContent = line;
      list.append(item);
    }
    alertBox.append(list);
  }
  if (log) {
    const pre = document.createElement('pre');
    pre.textContent = log;
    alertBox.append(pre);
  }
  alertBox.hidden = false;
}

export function clearError(): void {
  const alertBox = $('error');
  alertBox.hidden = true;
  alertBox.replaceChildren();
}

export function showIssues(source: string, issues: SceneIssue[]): void {
  showError(`${source} is not a valid scene; the current scene is kept.`, issues.map(formatIssue));
}

let noticeTimer = 0;
/** A passing message; `ms` = 0 keeps it until the next one. */
export function notify(text: string, ms = 4000): void {
  const notice = $('notice');
  notice.textContent = text;
  notice.hidden = false;
  clearTimeout(noticeTimer);
  if (ms > 0) noticeTimer = window.setTimeout(() => (notice.hidden = true), ms);
}

export function showFatal(title: string, detail: string, log?: string): void {
  const area = $('viewport-area');
  const box = document.createElement('div');
  box.className = 'fatal';
  const heading = document.createElement('h2');
  heading.textContent = title;
  const text = document.createElement('p');
  text.textContent = detail;
  box.append(heading, text);
  area.replaceChildren(box);
  showError(title, [detail], log);
  document.body.dataset.state = 'failed';
}
