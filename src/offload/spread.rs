//! A figure's work spread over a pool of workers (a browser's web workers, one per core): the
//! map's coarse first look and the statistics first, then the map's rows in tiles ([`TiledMap`]),
//! in any order and on any worker, then the map finished from all its masks. What the pool hands
//! back is assembled here into the map as it forms and, at the end, the figure's data: the data
//! [`crate::workspace::compute_figure_data`] computes in one piece.

use super::{Answer, Part, Request};
use crate::kinematics::Robot;
use crate::workspace::figure_data::PlaneMarks;
use crate::workspace::{
    Content, ContentRequest, FigureData, TILE_ROWS, TiledMap, WorkspaceMap, WorkspaceStats,
};
use std::collections::VecDeque;

/// What an answer to one of a spread figure's parts brought.
#[derive(Debug)]
pub enum SpreadStep {
    /// Nothing new to show.
    Working,
    /// The map as it forms (the tiles decided so far over the coarse look), and how many of its
    /// rows are decided.
    Partial(Box<WorkspaceMap>, usize),
    /// All of it: the figure's data.
    Done(Box<FigureData>),
}

/// A figure's work spread over a pool of workers (see the module documentation).
#[derive(Debug)]
pub struct Spread {
    request: Request,
    /// Parts not handed out yet.
    queue: VecDeque<Part>,
    /// Cells across and down of the map.
    dims: [usize; 2],
    /// The masks of the decided rows (0 elsewhere).
    masks: Vec<u8>,
    /// Which rows are decided.
    decided: Vec<bool>,
    /// Tiles not answered yet.
    tiles_left: usize,
    coarse: Option<WorkspaceMap>,
    stats: Option<(WorkspaceStats, Option<PlaneMarks>)>,
    map: Option<WorkspaceMap>,
}

impl Spread {
    /// The figure of `request` (for `robot`) spread over `workers` workers, in about three tiles
    /// per worker; `None` where it is not spread: a single worker, or a figure whose map is not
    /// made in tiles (it is then computed whole, [`Part::Whole`]).
    pub fn new(robot: &Robot, request: &Request, workers: usize) -> Option<Self> {
        let ContentRequest::Map(req) = &request.task.content else {
            return None;
        };
        if workers < 2 || !TiledMap::applies(robot, req) {
            return None;
        }
        let [w, h] = req.cells;
        let rows = h.div_ceil(3 * workers).next_multiple_of(TILE_ROWS);
        let tiles: Vec<Part> = (0..h)
            .step_by(rows)
            .map(|a| Part::Tile([a, (a + rows).min(h)]))
            .collect();
        Some(Self {
            request: request.for_part(Part::Whole),
            tiles_left: tiles.len(),
            queue: [Part::Coarse, Part::Stats]
                .into_iter()
                .chain(tiles)
                .collect(),
            dims: [w, h],
            masks: vec![0; w * h],
            decided: vec![false; h],
            coarse: None,
            stats: None,
            map: None,
        })
    }

    /// The next part to hand to an idle worker, if any is waiting (the map's finish waits for
    /// every tile).
    pub fn next_part(&mut self) -> Option<Request> {
        self.queue.pop_front().map(|p| self.request.for_part(p))
    }

    /// Takes a worker's answer to one of the parts.
    pub fn take(&mut self, answer: Answer) -> Result<SpreadStep, String> {
        let [w, h] = self.dims;
        match answer {
            Answer::Partial { map, rows_done: 0 } if map.masks.len() == w * h => {
                self.coarse = Some(*map);
            }
            Answer::Stats { stats, plane_marks } => self.stats = Some((*stats, plane_marks)),
            Answer::Tile {
                rows: [a, b],
                masks,
            } if a <= b && b <= h && masks.len() == (b - a) * w => {
                self.masks[a * w..b * w].copy_from_slice(&masks);
                self.decided[a..b].fill(true);
                self.tiles_left = self.tiles_left.saturating_sub(1);
                if self.tiles_left == 0 {
                    self.queue.push_front(Part::Finish(self.masks.clone()));
                }
            }
            Answer::Map(map) => self.map = Some(*map),
            Answer::Error(e) => return Err(e),
            other => return Err(format!("an answer that fits no part: {}", kind(&other))),
        }
        if let (Some(map), Some((stats, plane_marks))) = (&self.map, &self.stats) {
            return Ok(SpreadStep::Done(Box::new(FigureData {
                stats: stats.clone(),
                content: Content::Map(map.clone()),
                plane_marks: plane_marks.clone(),
            })));
        }
        Ok(match (&self.coarse, &self.map) {
            (Some(coarse), None) => {
                let mut map = coarse.clone();
                for (j, _) in self.decided.iter().enumerate().filter(|(_, d)| **d) {
                    map.masks[j * w..(j + 1) * w].copy_from_slice(&self.masks[j * w..(j + 1) * w]);
                }
                let done = self.decided.iter().filter(|d| **d).count();
                SpreadStep::Partial(Box::new(map), done)
            }
            _ => SpreadStep::Working,
        })
    }
}

/// The kind of an answer, in words.
fn kind(answer: &Answer) -> &'static str {
    match answer {
        Answer::Data(_) => "a figure's data",
        Answer::Partial { .. } => "a partial map",
        Answer::Stats { .. } => "statistics",
        Answer::Tile { .. } => "a tile",
        Answer::Map(_) => "a map",
        Answer::Error(_) => "an error",
    }
}
